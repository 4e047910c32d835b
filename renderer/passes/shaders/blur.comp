#version 450 core
// One axis of the separable 21-tap Gaussian (the thesis's blur). With BILATERAL, taps
// across a depth edge are down-weighted by their relative depth difference, so occlusion
// does not bleed from a foreground object onto the background behind it. Sky stays 1.
// Each invocation blurs kRun consecutive pixels along the axis from one window of
// kRun + 2 kRadius taps, so a pixel costs 3.5 loads instead of 21: on llvmpipe a load was
// most of a tap's cost, and the blur half of the 1080p SAO frame. Each pixel sums
// the same taps in the same order as a per-pixel loop, so the output is the same to the bit.
// Like SAO's blur, the first axis writes (AO, depth) pairs so the second reads one value per
// tap instead of two. RUN, GROUP, BILATERAL and SECOND_AXIS come from blur_pass.cpp.
layout(local_size_x = GROUP, local_size_y = GROUP) in;
uniform ivec2 u_size;
layout(std430, binding = 0) buffer Pairs { vec2 pairs[]; };  // (AO, depth), row by row
#ifdef SECOND_AXIS
vec2 tap(ivec2 q) { return pairs[q.y * u_size.x + q.x]; }
layout(std430, binding = 1) writeonly buffer Blurred { float blurred[]; };  // AO, row by row
void store(ivec2 p, vec2 v) { blurred[p.y * u_size.x + p.x] = v.x; }
#else
uniform sampler2D u_ao;  // R: AO
uniform sampler2D u_depth;
vec2 tap(ivec2 q) { return vec2(texelFetch(u_ao, q, 0).r, texelFetch(u_depth, q, 0).r); }
void store(ivec2 p, vec2 v) { pairs[p.y * u_size.x + p.x] = v; }
#endif
uniform ivec2 u_axis;       // (1, 0) or (0, 1)
uniform float u_sharpness;  // 1 / relative depth difference at which a tap's weight is 0

const int kRadius = 10;
const int kRun = RUN;
#if RUN != 8
#error "main() blurs eight pixels per invocation"
#endif
const int kWindow = kRun + 2 * kRadius;

int along(ivec2 v) { return v.x * u_axis.x + v.y * u_axis.y; }
// exp(-i^2 / (2 sigma^2)), sigma = 4, i = 0..10 (RendererBlur.* checks the normalized kernel)
const float kWeight[kRadius + 1] = float[](1.0, 0.969233234, 0.882496903, 0.754839602,
    0.606530660, 0.457833362, 0.324652467, 0.216265167, 0.135335283, 0.0795595087, 0.0439369336);

void blur_pixel(vec2 window[kWindow], ivec2 first, int j, int last) {
  ivec2 p = first + j * u_axis;
  if (along(p) > last) return;
  vec2 centre = window[j + kRadius];
  float z = centre.y;
#ifdef BILATERAL
  float k = z > 0.0 ? u_sharpness / z : 0.0;
#endif
  float sum = 0.0, wsum = 0.0;
  for (int i = -kRadius; i <= kRadius; ++i) {
    vec2 t = window[j + kRadius + i];
    // Sky taps (depth 0) weigh nothing.
    float w = kWeight[abs(i)] * float(t.y > 0.0);
#ifdef BILATERAL
    w *= max(0.0, 1.0 - k * abs(t.y - z));
#endif
    sum += w * t.x;
    wsum += w;
  }
  // Sky (z = 0) stays 1: every tap weighs 0 there. One store for both, not one per branch.
  store(p, z > 0.0 ? vec2(wsum > 0.0 ? sum / wsum : centre.x, z) : vec2(1.0, 0.0));
}

void main() {
  ivec2 hi = u_size - 1;
  ivec2 across = ivec2(1) - u_axis;
  // Invocation (x, y) of the horizontal axis runs pixels (kRun x .. kRun x + kRun - 1, y).
  ivec2 first = ivec2(gl_GlobalInvocationID.xy) * (u_axis * kRun + across);
  int last = along(hi);
  if (any(greaterThan(first, hi))) return;
  vec2 window[kWindow];
  for (int j = 0; j < kWindow; ++j) {
    window[j] = tap(clamp(first + (j - kRadius) * u_axis, ivec2(0), hi));
  }
  // Unrolled by hand so that every window index is a constant: with a loop over j the window
  // stayed an array indexed at run time, which doubled the pass's time on llvmpipe.
  blur_pixel(window, first, 0, last);
  blur_pixel(window, first, 1, last);
  blur_pixel(window, first, 2, last);
  blur_pixel(window, first, 3, last);
  blur_pixel(window, first, 4, last);
  blur_pixel(window, first, 5, last);
  blur_pixel(window, first, 6, last);
  blur_pixel(window, first, 7, last);
}

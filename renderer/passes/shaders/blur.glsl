// One axis of the separable 21-tap Gaussian (the thesis's blur), shared by blur.comp (runs of
// pixels per invocation, for a CPU rasteriser) and blur_tile.comp (a pixel per invocation
// through shared memory, for GPUs). With BILATERAL, taps across a depth edge are down-weighted
// by their relative depth difference, so occlusion does not bleed from a foreground object onto
// the background behind it. Sky stays 1. Both kernels sum the same taps in the same order, so
// their output is the same to the bit. Like SAO's blur, the first axis writes (AO, depth) pairs
// so the second reads one value per tap instead of two. BILATERAL, SECOND_AXIS and
// STORE_TEXTURE come from blur_pass.cpp.
uniform ivec2 u_size;
layout(std430, binding = 0) buffer Pairs { vec2 pairs[]; };  // (AO, depth), row by row
#ifdef SECOND_AXIS
vec2 tap(ivec2 q) { return pairs[q.y * u_size.x + q.x]; }
#ifdef STORE_TEXTURE
layout(r32f, binding = 0) writeonly uniform image2D u_ao_out;
void store(ivec2 p, vec2 v) { imageStore(u_ao_out, p, vec4(v.x)); }
#else
layout(std430, binding = 1) writeonly buffer Blurred { float blurred[]; };  // AO, row by row
void store(ivec2 p, vec2 v) { blurred[p.y * u_size.x + p.x] = v.x; }
#endif
#else
uniform sampler2D u_ao;  // R: AO
uniform sampler2D u_depth;
vec2 tap(ivec2 q) { return vec2(texelFetch(u_ao, q, 0).r, texelFetch(u_depth, q, 0).r); }
void store(ivec2 p, vec2 v) { pairs[p.y * u_size.x + p.x] = v; }
#endif
uniform ivec2 u_axis;       // (1, 0) or (0, 1)
uniform float u_sharpness;  // 1 / relative depth difference at which a tap's weight is 0

const int kRadius = 10;

int along(ivec2 v) { return v.x * u_axis.x + v.y * u_axis.y; }
// exp(-i^2 / (2 sigma^2)), sigma = 4, i = 0..10 (RendererBlur.* checks the normalized kernel)
const float kWeight[kRadius + 1] = float[](1.0, 0.969233234, 0.882496903, 0.754839602,
    0.606530660, 0.457833362, 0.324652467, 0.216265167, 0.135335283, 0.0795595087, 0.0439369336);

// The kernel's window: tap k of the line this invocation blurs, its pixels' taps side by side
// (the includer defines it).
vec2 window_tap(int k);

// The blurred (AO, depth) of the pixel at window_tap(j + kRadius).
vec2 blurred_pair(int j) {
  vec2 centre = window_tap(j + kRadius);
  float z = centre.y;
#ifdef BILATERAL
  float k = z > 0.0 ? u_sharpness / z : 0.0;
#endif
  float sum = 0.0, wsum = 0.0;
  for (int i = -kRadius; i <= kRadius; ++i) {
    vec2 t = window_tap(j + kRadius + i);
    // Sky taps (depth 0) weigh nothing.
    float w = kWeight[abs(i)] * float(t.y > 0.0);
#ifdef BILATERAL
    w *= max(0.0, 1.0 - k * abs(t.y - z));
#endif
    sum += w * t.x;
    wsum += w;
  }
  // Sky (z = 0) stays 1: every tap weighs 0 there. One store for both, not one per branch.
  return z > 0.0 ? vec2(wsum > 0.0 ? sum / wsum : centre.x, z) : vec2(1.0, 0.0);
}

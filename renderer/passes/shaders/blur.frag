#version 450 core
// One axis of the separable 21-tap Gaussian (the thesis's blur). With u_bilateral, taps
// across a depth edge are down-weighted by their relative depth difference, so occlusion
// does not bleed from a foreground object onto the background behind it. Sky stays 1.
// Like SAO's blur, the first axis writes (AO, depth) pairs so the second reads one texel per
// tap instead of two: on llvmpipe each fetch is most of a tap's cost.
#ifdef PACKED_INPUT
uniform sampler2D u_ao;  // RG: AO, linear depth
vec2 tap(ivec2 q) { return texelFetch(u_ao, q, 0).rg; }
#else
uniform sampler2D u_ao;  // R: AO
uniform sampler2D u_depth;
vec2 tap(ivec2 q) { return vec2(texelFetch(u_ao, q, 0).r, texelFetch(u_depth, q, 0).r); }
#endif
uniform ivec2 u_axis;
uniform bool u_bilateral;
uniform float u_sharpness;  // 1 / relative depth difference at which a tap's weight is 0
layout(location = 0) out vec2 o_ao;

const int kRadius = 10;
// exp(-i^2 / (2 sigma^2)), sigma = 4, i = 0..10 (RendererBlur.* checks the normalized kernel)
const float kWeight[kRadius + 1] = float[](1.0, 0.969233234, 0.882496903, 0.754839602,
    0.606530660, 0.457833362, 0.324652467, 0.216265167, 0.135335283, 0.0795595087, 0.0439369336);

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 hi = textureSize(u_ao, 0) - 1;
  vec2 centre = tap(p);
  float z = centre.y;
  if (z <= 0.0) { o_ao = vec2(1.0, 0.0); return; }
  float k = u_bilateral ? u_sharpness / z : 0.0;
  float sum = 0.0, wsum = 0.0;
  for (int i = -kRadius; i <= kRadius; ++i) {
    vec2 t = tap(clamp(p + i * u_axis, ivec2(0), hi));
    // Sky taps (depth 0) weigh nothing.
    float w = kWeight[abs(i)] * max(0.0, 1.0 - k * abs(t.y - z)) * float(t.y > 0.0);
    sum += w * t.x;
    wsum += w;
  }
  o_ao = vec2(wsum > 0.0 ? sum / wsum : centre.x, z);
}

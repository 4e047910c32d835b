#version 450 core
// One axis of the separable 21-tap Gaussian (the thesis's blur). With u_bilateral, taps
// across a depth edge are down-weighted by their relative depth difference, so occlusion
// does not bleed from a foreground object onto the background behind it. Sky stays 1.
uniform sampler2D u_ao;
uniform sampler2D u_depth;
uniform ivec2 u_axis;
uniform bool u_bilateral;
uniform float u_sharpness;  // 1 / relative depth difference at which a tap's weight is 0
layout(location = 0) out float o_ao;

const int kRadius = 10;
const float kSigma = 4.0;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 hi = textureSize(u_ao, 0) - 1;
  float z = texelFetch(u_depth, p, 0).r;
  if (z <= 0.0) { o_ao = 1.0; return; }
  float sum = 0.0, wsum = 0.0;
  for (int i = -kRadius; i <= kRadius; ++i) {
    ivec2 q = clamp(p + i * u_axis, ivec2(0), hi);
    float zq = texelFetch(u_depth, q, 0).r;
    if (zq <= 0.0) continue;
    float w = exp(-float(i * i) / (2.0 * kSigma * kSigma));
    if (u_bilateral) w *= max(0.0, 1.0 - u_sharpness * abs(zq - z) / z);
    sum += w * texelFetch(u_ao, q, 0).r;
    wsum += w;
  }
  o_ao = wsum > 0.0 ? sum / wsum : texelFetch(u_ao, p, 0).r;
}

#include "alchemy_estimator.glsl"
#include "bilateral_upsample.glsl"
// One level of Multi-Scale AO, coarse to fine. Local occlusion O = 1 - Alchemy(level) with
// the level's own intensity; combined with the bilaterally upsampled coarser result as
// (max, sum) in RG: R = max(O, up.R), G = O + up.G. The finest level writes visibility
// A = (1 - R) * (1 - G / levels), i.e. occlusion 1 - (1 - max)(1 - average) as in
// Hoang & Low's slides (AO_final >= max and grows with the average).
uniform sampler2D u_depth;
uniform sampler2D u_normal;
uniform sampler2D u_coarse;        // RG of the next coarser level
uniform sampler2D u_coarse_depth;
uniform sampler2D u_coarse_normal;
uniform bool u_has_coarse;
uniform bool u_local;              // false: this level's weight is 0, only pass through
uniform bool u_finest;
uniform float u_levels;            // levels that contribute, for the average

// The level's texel at p: (max, sum) of occlusion, or visibility on the finest level.
vec4 mssao_level(ivec2 p) {
  float z = texelFetch(u_depth, p, 0).r;
  if (z <= 0.0) return u_finest ? vec4(1.0) : vec4(0.0);
  vec3 n = safe_normalize(texelFetch(u_normal, p, 0).xyz);
  float local = u_local ? 1.0 - alchemy_ao(u_depth, p, z, n) : 0.0;
  vec2 up = u_has_coarse
                ? bilateral_upsample(u_coarse, u_coarse_depth, u_coarse_normal, p, z, n, vec2(0.0))
                : vec2(0.0);
  vec2 combined = vec2(max(local, up.x), local + up.y);
  if (u_finest) {
    float a = (1.0 - combined.x) * (1.0 - combined.y / max(u_levels, 1.0));
    return vec4(clamp(a, 0.0, 1.0));
  }
  return vec4(combined, 0.0, 0.0);
}

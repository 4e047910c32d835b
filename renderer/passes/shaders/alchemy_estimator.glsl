// Alchemy AO (McGuire et al. 2011):
//   A = max(0, 1 - (2 sigma r / s) * sum_i max(0, v_i.n - z beta) / (v_i.v_i + eps r^2))^k
// Taps on SAO's spiral within the world-space radius r. The factor r (Unity's form of the
// implicit falloff u) and eps scaled by r^2 make the estimator independent of scene scale;
// at r = 1 they are the published constants (eps = 1e-4).
// u_bias is beta, in metres per metre of depth; u_contrast is k.
#include "ao_uniforms.glsl"

float alchemy_ao(sampler2D depth, ivec2 p, float z, vec3 n) {
  vec2 size = vec2(textureSize(depth, 0));
  vec3 c = view_position(vec2(p) + 0.5, size, z);
  float ss_radius = min(u_proj_scale * u_radius / z, u_max_pixel_radius);
  float spin = spin_angle(p);
  float r2 = u_radius * u_radius;
  float sum = 0.0;
  for (int i = 0; i < u_samples; ++i) {
    float a = (float(i) + 0.5) / float(u_samples);
    float angle = a * u_turns * 6.2831853 + spin;
    vec2 offset = vec2(cos(angle), sin(angle)) * max(a * ss_radius, 1.0);
    ivec2 q = clamp(ivec2(floor(vec2(p) + 0.5 + offset)), ivec2(0), ivec2(size) - 1);
    float zq = texelFetch(depth, q, 0).r;
    if (zq <= 0.0) continue;  // sky occludes nothing
    vec3 v = view_position(vec2(q) + 0.5, size, zq) - c;
    float vv = dot(v, v);
    if (vv > r2) continue;
    sum += max(0.0, dot(v, n) - z * u_bias) / (vv + 1e-4 * r2);
  }
  float a = max(0.0, 1.0 - 2.0 * u_intensity * u_radius / float(max(u_samples, 1)) * sum);
  return pow(a, u_contrast);
}

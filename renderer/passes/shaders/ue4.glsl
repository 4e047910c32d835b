// Unreal Engine 4 AO (Mittring 2012): HBAO-like. For each of s directions (rotated by a
// 4x4 tiled pattern) take samples at 3 equidistant steps on both sides of the pixel; per
// side keep the highest elevation above the G-buffer normal's tangent plane,
// e = max saturate(v.n / |v| - bias); a pair's visibility is ((1-e_l)^2 + (1-e_r)^2) / 2
// ("the area scales quadratically with the angle"). Samples beyond the radius are ignored
// (halo guard). A = 1 - (1 - vis^power) * intensity.
uniform sampler2D u_depth;
uniform sampler2D u_normal;
#include "ao_uniforms.glsl"  // u_contrast is the power

const int kSteps = 3;

float horizon(ivec2 p, vec2 dir, float ss_radius, vec3 c, vec3 n, vec2 size) {
  float e = 0.0;
  float r2 = u_radius * u_radius;
  for (int j = 0; j < kSteps; ++j) {
    float t = max(float(j + 1) / float(kSteps) * ss_radius, 1.0);
    ivec2 q = clamp(ivec2(floor(vec2(p) + 0.5 + t * dir)), ivec2(0), ivec2(size) - 1);
    float zq = texelFetch(u_depth, q, 0).r;
    if (zq <= 0.0) continue;
    vec3 v = view_position(vec2(q) + 0.5, size, zq) - c;
    float vv = dot(v, v);
    if (vv > r2 || vv <= 0.0) continue;
    e = max(e, clamp(dot(v, n) * inversesqrt(vv) - u_bias, 0.0, 1.0));
  }
  return e;
}

float estimate_ao(ivec2 p) {
  vec2 size = vec2(textureSize(u_depth, 0));
  float z = texelFetch(u_depth, p, 0).r;
  if (z <= 0.0) return 1.0;
  vec3 c = view_position(vec2(p) + 0.5, size, z);
  vec3 n = safe_normalize(texelFetch(u_normal, p, 0).xyz);
  float ss_radius = u_proj_scale * u_radius / z;
  float jitter = float((p.x & 3) * 4 + (p.y & 3)) / 16.0;
  int dirs = max(u_samples, 1);
  float vis = 0.0;
  for (int k = 0; k < dirs; ++k) {
    float angle = (float(k) + jitter) / float(dirs) * 3.14159265;
    vec2 d = vec2(cos(angle), sin(angle));
    float l = 1.0 - horizon(p, d, ss_radius, c, n, size);
    float r = 1.0 - horizon(p, -d, ss_radius, c, n, size);
    vis += 0.5 * (l * l + r * r);
  }
  vis /= float(dirs);
  return clamp(1.0 - (1.0 - pow(vis, u_contrast)) * u_intensity, 0.0, 1.0);
}

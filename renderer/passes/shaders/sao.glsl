// Scalable AO (McGuire, Mara, Luebke 2012): depth only. Normals come from depth, taps follow
// a spiral and read a coarser level of the depth pyramid the further out they land.
// Per tap f = max(r^2 - v.v, 0)^3 * max((v.n - beta) / (v.v + eps r^2), 0);
// A = max(0, 1 - sum * sigma / r^5 * 5 / s). At r = 1 this is the reference's
// sigma / r^6 with eps = 0.01; the extra r keeps the result independent of scene scale.
// beta = u_bias * r: the reference subtracts SAO::Settings' bias 0.012 from v.n in absolute
// scene units (design/ao-techniques.md 3.2), so with the scene scaled to 1e-5 it swallowed
// every v.n and nothing occluded. As a share of r it is the published 0.012 at r = 1, and f
// scales as r^5 (r^6 * r / r^2) like the normalization, so A does not depend on scene units.
#include "sao_pyramid.glsl"
#include "ao_uniforms.glsl"

const int kLogMaxOffset = 3;

// The full-resolution pixel whose depth sao_pyramid.comp kept for texel q of level m. Each
// level keeps texel 2q + (q.y & 1, q.x & 1) of the level below, so going down the offsets
// alternate between (b.y, b.x) and (b.x, b.y), b = q & 1: a closed form (a loop over the
// levels cost a fifth of the pass on llvmpipe).
ivec2 pyramid_source(ivec2 q, int m) {
  ivec2 b = q & 1;
  int odd = 0xAAAA >> (16 - m), even = 0x5555 >> (16 - m);
  return (q << m) + b.yx * odd + b * even;
}

vec3 position_at(ivec2 q, vec2 size) {
  float z = pyramid_depth(q, 0);
  return z > 0.0 ? view_position(vec2(q) + 0.5, size, z) : vec3(0.0);
}

#include "depth_normal.glsl"

float estimate_ao(ivec2 p) {
  vec2 size = vec2(u_size);
  float z = pyramid_depth(p, 0);
  if (z <= 0.0) return 1.0;
  vec3 c = view_position(vec2(p) + 0.5, size, z);
  vec3 n = depth_normal(p, c, size);
  if (dot(n, n) < 0.5) return 1.0;  // no surface to speak of
  float ss_radius = u_proj_scale * u_radius / z;
  float spin = spin_angle(p);
  float r2 = u_radius * u_radius;
  float beta = u_bias * u_radius;
  float sum = 0.0;
  // Tap i lies at angle (i + 0.5) * step + spin: rotate one direction per tap instead of two
  // trigonometric calls.
  float step_angle = u_turns * 6.28 / float(u_samples);
  vec2 dir = vec2(cos(spin + 0.5 * step_angle), sin(spin + 0.5 * step_angle));
  mat2 rotate = mat2(cos(step_angle), sin(step_angle), -sin(step_angle), cos(step_angle));
  for (int i = 0; i < u_samples; ++i, dir = rotate * dir) {
    float a = (float(i) + 0.5) / float(u_samples);
    float h = a * ss_radius;
    ivec2 q = ivec2(floor(vec2(p) + 0.5 + h * dir));
    int m = clamp(findMSB(max(int(h), 1)) - kLogMaxOffset, 0, u_levels - 1);
    ivec2 qm = clamp(q >> m, ivec2(0), level_size(m) - 1);
    float zq = pyramid_depth(qm, m);
    if (zq <= 0.0) continue;
    // The reference unprojects zq at the tap's own pixel, but zq belongs to a pixel up to 2^m
    // away: on a steep depth gradient (a ground plane seen at grazing angles) that lifts the
    // point off the surface and draws dark streaks. Unprojecting at the pixel zq came from
    // keeps every tap on a real surface.
    ivec2 src = min(pyramid_source(qm, m), ivec2(size) - 1);
    vec3 v = view_position(vec2(src) + 0.5, size, zq) - c;
    float vv = dot(v, v);
    float f = max(r2 - vv, 0.0);
    sum += f * f * f * max((dot(v, n) - beta) / (vv + 0.01 * r2), 0.0);
  }
  float r5 = r2 * r2 * u_radius;
  float a = max(0.0, 1.0 - sum * u_intensity / r5 * 5.0 / float(max(u_samples, 1)));
  return pow(a, u_contrast);
}

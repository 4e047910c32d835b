#version 450 core
#include "common.glsl"
// Ground-Truth AO (Jimenez, Wu, Pesce & Jarabo 2016, "Practical Realtime Strategies for
// Accurate Indirect Occlusion", Algorithm 1), with the constants of Intel's XeGTAO "High"
// preset (design/ao-techniques.md section 6.4). Per pixel, u_slices screen-space slices at
// angles phi in [0, pi); in each, the horizon on both sides from u_steps samples per side;
// the cosine-weighted visible arc between the horizons integrated in closed form (eq. 10) and
// weighted by the projected normal's length (eq. 8 / Algorithm 1 line 27). Visibility is 1 on
// an unoccluded plane.
uniform sampler2D u_depth;
uniform sampler2D u_normal;
#include "ao_uniforms.glsl"  // u_contrast is XeGTAO's FinalValuePower
layout(location = 0) out float o_ao;

const float kPi = 3.14159265;
const float kRadiusMultiplier = 1.457;   // XeGTAO: radius as the RT reference tuned it
const float kSampleDistributionPower = 2.0;  // more samples near the centre
const float kMinVisibility = 0.03;

// Per-pixel noise: the slice angle's offset from a 4x4 Bayer matrix, so any 4x4 block of
// pixels holds 16 evenly spaced slice rotations and the blur that follows integrates over
// them (XeGTAO drives an R2 sequence with a Hilbert index to the same end, for its 3x3
// denoiser); the step offset from R2 over the pixel's place in a 64x64 tile.
vec2 slice_and_step_noise(ivec2 p) {
  const float bayer[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0,
                                    9.0, 15.0, 7.0, 13.0, 5.0);
  float slice = (bayer[(p.y & 3) * 4 + (p.x & 3)] + 0.5) / 16.0;
  float index = float((p.y & 63) * 64 + (p.x & 63));
  return vec2(slice, fract(0.5 + index * 0.5698402910));
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 size = vec2(textureSize(u_depth, 0));
  float z = texelFetch(u_depth, p, 0).r;
  if (z <= 0.0) { o_ao = 1.0; return; }
  vec3 centre = view_position(vec2(p) + 0.5, size, z * 0.99999);  // XeGTAO's fp32 nudge
  vec3 view = safe_normalize(-centre);
  vec3 normal = safe_normalize(texelFetch(u_normal, p, 0).xyz);

  float radius = u_radius * kRadiusMultiplier;
  float falloff_range = max(u_falloff_range * radius, 1e-6);
  float falloff_from = radius * (1.0 - u_falloff_range);
  // weight = saturate(distance * falloff_mul + falloff_add): 1 up to falloff_from, 0 at radius
  float falloff_mul = -1.0 / falloff_range;
  float falloff_add = falloff_from / falloff_range + 1.0;

  float screen_radius = radius * u_proj_scale / z;  // pixels
  // Fade out where the radius covers few pixels (XeGTAO): few samples would land off the pixel.
  float visibility = clamp((10.0 - screen_radius) / 100.0, 0.0, 1.0) * 0.5;
  if (screen_radius < 1.3) { o_ao = 1.0; return; }  // the whole kernel inside the pixel
  float min_s = 1.3 / screen_radius;  // the first sample leaves the centre pixel

  vec2 noise = slice_and_step_noise(p);
  int slices = max(u_slices, 1), steps = max(u_steps, 1);
  for (int slice = 0; slice < slices; ++slice) {
    float phi = (float(slice) + noise.x) / float(slices) * kPi;
    // Screen rows run up here as view-space y does, so one direction serves both.
    vec2 omega = vec2(cos(phi), sin(phi));
    vec3 direction = vec3(omega, 0.0);
    vec3 ortho_direction = direction - dot(direction, view) * view;
    vec3 axis = safe_normalize(cross(ortho_direction, view));
    vec3 projected_normal = normal - axis * dot(normal, axis);
    float projected_length = length(projected_normal);
    if (projected_length < 1e-6) continue;  // the normal along the slice axis: no arc
    float sign_n = dot(ortho_direction, projected_normal) >= 0.0 ? 1.0 : -1.0;
    float cos_n = clamp(dot(projected_normal, view) / projected_length, 0.0, 1.0);
    float n = sign_n * acos(cos_n);  // the projected normal's angle from the view vector
    // Below the tangent plane nothing can occlude: the horizons start there.
    float low_cos0 = cos(n + 0.5 * kPi), low_cos1 = cos(n - 0.5 * kPi);
    float horizon_cos0 = low_cos0, horizon_cos1 = low_cos1;
    for (int step = 0; step < steps; ++step) {
      float step_noise = fract(noise.y + float(slice + step * steps) * 0.6180339887);
      float s = pow((float(step) + step_noise) / float(steps), kSampleDistributionPower) + min_s;
      vec2 offset = s * screen_radius * omega;
      for (int side = 0; side < 2; ++side) {
        vec2 at = vec2(p) + 0.5 + (side == 0 ? offset : -offset);
        if (any(lessThan(at, vec2(0.0))) || any(greaterThanEqual(at, size))) continue;
        ivec2 q = ivec2(at);
        float zq = texelFetch(u_depth, q, 0).r;
        if (zq <= 0.0) continue;  // sky occludes nothing
        vec3 delta = view_position(vec2(q) + 0.5, size, zq) - centre;
        float distance = length(delta);
        if (distance <= 0.0) continue;
        // Thin occluders: stretching the depth difference fades samples far behind the
        // surface sooner, so thin objects cast thinner halos (0 = off, XeGTAO's default).
        float falloff_base = length(vec3(delta.xy, delta.z * (1.0 + u_thin_occluder)));
        float weight = clamp(falloff_base * falloff_mul + falloff_add, 0.0, 1.0);
        float sample_cos = dot(delta / distance, view);
        if (side == 0) {
          horizon_cos0 = max(horizon_cos0, mix(low_cos0, sample_cos, weight));
        } else {
          horizon_cos1 = max(horizon_cos1, mix(low_cos1, sample_cos, weight));
        }
      }
    }
    // Horizon angles from the view vector, side 1 negative (Algorithm 1 lines 19-20).
    float h0 = -acos(clamp(horizon_cos1, -1.0, 1.0));
    float h1 = acos(clamp(horizon_cos0, -1.0, 1.0));
    // The cosine-weighted arc between them (eq. 10): 1 in all for an open plane.
    float arc0 = (cos_n + 2.0 * h0 * sin(n) - cos(2.0 * h0 - n)) * 0.25;
    float arc1 = (cos_n + 2.0 * h1 * sin(n) - cos(2.0 * h1 - n)) * 0.25;
    // XeGTAO's fudge: mix(|n_p|, 1, 0.05) tracks its ray-traced reference better.
    visibility += mix(projected_length, 1.0, 0.05) * (arc0 + arc1);
  }
  visibility /= float(slices);
  visibility = max(kMinVisibility, pow(clamp(visibility, 0.0, 1.0), u_contrast));
  o_ao = clamp(1.0 - (1.0 - visibility) * u_intensity, 0.0, 1.0);
}

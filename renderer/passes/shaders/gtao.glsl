// Ground-Truth AO (Jimenez, Wu, Pesce & Jarabo 2016, "Practical Realtime Strategies for
// Accurate Indirect Occlusion", Algorithm 1), with the constants of Intel's XeGTAO "High"
// preset (design/ao-techniques.md section 6.4). Per pixel, u_slices screen-space slices at
// angles phi in [0, pi); in each, the horizon on both sides from u_steps samples per side;
// the cosine-weighted visible arc between the horizons integrated in closed form (eq. 10) and
// weighted by the projected normal's length (eq. 8 / Algorithm 1 line 27). That is 1 for an
// unoccluded plane only on average over the slice angle, and XeGTAO's samples snap to texel
// centres, off the slice, where a slanted plane can rise above the slice's tangent: with
// u_exact_plane, samples stay on the slice and the arcs are divided by an open plane's, so an
// open plane is exactly 1 (results.md: the darkening each part causes).
uniform sampler2D u_depth;
uniform sampler2D u_normal;
#include "ao_uniforms.glsl"  // u_contrast is XeGTAO's FinalValuePower
#include "slice_sampling.glsl"  // kPi, slice_and_step_noise, step_distance, make_slice

const float kRadiusMultiplier = 1.457;   // XeGTAO: radius as the RT reference tuned it
const float kMinVisibility = 0.03;

// The view-space point a horizon sample stands for, at screen position `at`; false on sky.
// Snapped: the texel under it (XeGTAO). Exact: the depth at `at` itself, interpolated in 1/z
// (affine in screen space on a plane) from the four texels around it, one gather.
bool sample_point(vec2 at, vec2 size, out vec3 point) {
  if (u_exact_plane == 0) {
    float z = texelFetch(u_depth, ivec2(at), 0).r;
    point = view_position(floor(at) + 0.5, size, z);
    return z > 0.0;
  }
  vec2 corner = clamp(floor(at - 0.5), vec2(0.0), size - 2.0) + 1.0;  // between four centres
  vec4 z = textureGather(u_depth, corner / size, 0);  // (0,1) (1,1) (1,0) (0,0) around it
  if (min(min(z.x, z.y), min(z.z, z.w)) <= 0.0) return false;  // sky among them
  vec2 t = clamp(at - (corner - 0.5), 0.0, 1.0);
  vec4 inv = 1.0 / z;
  float inv_z = mix(mix(inv.w, inv.z, t.x), mix(inv.x, inv.y, t.x), t.y);
  point = view_position(at, size, 1.0 / inv_z);
  return true;
}

float estimate_ao(ivec2 p) {
  vec2 size = vec2(textureSize(u_depth, 0));
  float z = texelFetch(u_depth, p, 0).r;
  if (z <= 0.0) return 1.0;
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
  float fade = clamp((10.0 - screen_radius) / 100.0, 0.0, 1.0) * 0.5;
  float visible = 0.0, open = 0.0;  // sums over the slices
  if (screen_radius < 1.3) return 1.0;  // the whole kernel inside the pixel
  float min_s = 1.3 / screen_radius;  // the first sample leaves the centre pixel

  vec2 noise = slice_and_step_noise(p);
  int slices = max(u_slices, 1), steps = max(u_steps, 1);
  for (int slice = 0; slice < slices; ++slice) {
    Slice sl;
    if (!make_slice(slice, slices, noise.x, view, normal, sl)) continue;
    vec2 omega = sl.omega;
    float cos_n = sl.cos_n, n = sl.n;
    // Below the tangent plane nothing can occlude: the horizons start there.
    float low_cos0 = cos(n + 0.5 * kPi), low_cos1 = cos(n - 0.5 * kPi);
    float horizon_cos0 = low_cos0, horizon_cos1 = low_cos1;
    for (int step = 0; step < steps; ++step) {
      float s = step_distance(noise.y, slice, step, steps, min_s);
      vec2 offset = s * screen_radius * omega;
      for (int side = 0; side < 2; ++side) {
        vec2 at = vec2(p) + 0.5 + (side == 0 ? offset : -offset);
        if (any(lessThan(at, vec2(0.0))) || any(greaterThanEqual(at, size))) continue;
        vec3 point;
        if (!sample_point(at, size, point)) continue;  // sky occludes nothing
        vec3 delta = point - centre;
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
    float weight = mix(sl.projected_length, 1.0, 0.05);
    visible += weight * (arc0 + arc1);
    // The same arcs with both horizons on the tangent plane, h = n -+ pi/2 (eq. 10).
    open += weight * (cos_n + n * sin(n));
  }
  float visibility = u_exact_plane == 0 ? (fade + visible) / float(slices)
                                        : fade / float(slices) + (open > 1e-6 ? visible / open : 1.0);
  visibility = max(kMinVisibility, pow(clamp(visibility, 0.0, 1.0), u_contrast));
  return clamp(1.0 - (1.0 - visibility) * u_intensity, 0.0, 1.0);
}

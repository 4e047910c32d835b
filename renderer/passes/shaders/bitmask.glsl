// Visibility-bitmask AO (Therrien, Levesque & Gilet 2023, "Screen Space Indirect Lighting
// with Visibility Bitmask"; design/ao-techniques.md section 6.4b): GTAO's slices and steps
// (gtao.glsl, slice_sampling.glsl), but each slice keeps one bit per sector of its half-circle
// instead of one horizon angle per side. A sample occludes only the sectors between its front
// angle theta_f and its back angle theta_b, the angle of the sample pushed u_thickness away
// from the eye: occluders are slabs of constant thickness, so light passes behind thin ones.
//
// Weighting: the sectors are uniform in angle, as in the paper, but each counts with its
// cosine-weighted measure, GTAO's inner integral (its eq. 10) over the sector, so the result
// estimates the cosine-weighted AO that the ray-traced reference computes. The slices are
// combined as the ratio of visible to total measure, each slice weighted by its projected
// normal's length (GTAO eq. 8): an open plane gives exactly 1 at any slice angle.
uniform sampler2D u_depth;
uniform sampler2D u_normal;
#include "ao_uniforms.glsl"  // u_thickness: a share of u_radius; u_contrast: final power
#include "slice_sampling.glsl"  // GTAO's kPi, noise, step_distance, make_slice

const int kSectors = 32;  // one uint per slice, as in the paper

// The slice's cosine-weighted measure between the view vector (theta = 0) and theta, for the
// projected normal at angle n: the integral of cos(t - n) |sin t| dt (GTAO eq. 10 per side,
// with the side's sign). It rises monotonically across the hemisphere [n - pi/2, n + pi/2].
float cosine_measure(float theta, float n) {
  float side = 0.25 * (cos(n) + 2.0 * theta * sin(n) - cos(2.0 * theta - n));
  return theta < 0.0 ? -side : side;
}

// Angle of sector boundary i (0..32) from the view vector: sectors split the hemisphere
// above the tangent plane, [n - pi/2, n + pi/2], into equal angles.
float sector_angle(int i, float n) { return n - 0.5 * kPi + float(i) * (kPi / float(kSectors)); }

// The measure of the set bits, one integral per run of consecutive set bits (at most 16
// runs) rather than one per bit.
float occluded_measure(uint bits, float n) {
  float sum = 0.0;
  while (bits != 0u) {
    int start = findLSB(bits);
    uint rest = ~(bits >> uint(start));  // zeros where the run goes on
    int end = rest == 0u ? kSectors : start + findLSB(rest);
    sum += cosine_measure(sector_angle(end, n), n) - cosine_measure(sector_angle(start, n), n);
    bits &= end >= kSectors ? 0u : ~0u << uint(end);  // shifting by 32 is undefined
  }
  return sum;
}

// The sectors between two slice positions in [0, 1]: floor for the lower edge and ceil for the
// upper one (the paper's rounding), so any occluder inside the hemisphere sets a sector.
uint sector_bits(float lo, float hi) {
  int start = int(floor(clamp(lo, 0.0, 1.0) * float(kSectors)));
  int end = int(ceil(clamp(hi, 0.0, 1.0) * float(kSectors)));
  int count = end - start;
  if (count <= 0) return 0u;  // both outside the hemisphere, on the same side
  uint run = count >= kSectors ? ~0u : (1u << uint(count)) - 1u;
  return run << uint(start);  // count > 0 keeps start <= 31
}

float estimate_ao(ivec2 p) {
  vec2 size = vec2(textureSize(u_depth, 0));
  float z = texelFetch(u_depth, p, 0).r;
  if (z <= 0.0) return 1.0;
  vec3 centre = view_position(vec2(p) + 0.5, size, z * 0.99999);  // XeGTAO's fp32 nudge
  vec3 view = safe_normalize(-centre);
  vec3 normal = safe_normalize(texelFetch(u_normal, p, 0).xyz);

  // The kernel reaches u_radius, where the reference's rays stop; a sample farther away in
  // the scene is no occluder, as a ray hit beyond r is none (binary, like V_r). Not XeGTAO's
  // 1.457 u_radius: with this hard cut, the same steps spread over the wider disc found fewer
  // occluders (error against the reference rose on all six built-in views tried).
  float radius = u_radius;
  // Capped so an absurd radius cannot make offsets Inf (and Inf * 0 NaN).
  float screen_radius = min(radius * u_proj_scale / z, 1e6);  // pixels
  if (!(screen_radius >= 1.3)) return 1.0;  // the whole kernel inside the pixel
  float min_s = 1.3 / screen_radius;  // the first sample leaves the centre pixel
  float thickness = u_thickness * radius;  // a share of the radius: the same at every scale

  vec2 noise = slice_and_step_noise(p);
  int slices = max(u_slices, 1), steps = max(u_steps, 1);
  float visible = 0.0, total = 0.0;  // cosine-weighted measures, summed over the slices
  for (int slice = 0; slice < slices; ++slice) {
    Slice sl;
    if (!make_slice(slice, slices, noise.x, view, normal, sl)) continue;
    vec2 omega = sl.omega;
    float n = sl.n;
    uint occluded = 0u;
    for (int step = 0; step < steps; ++step) {
      float s = step_distance(noise.y, slice, step, steps, min_s);
      vec2 offset = s * screen_radius * omega;
      for (int side = 0; side < 2; ++side) {
        vec2 at = vec2(p) + 0.5 + (side == 0 ? offset : -offset);
        // Written so that a NaN position fails too.
        if (!(all(greaterThanEqual(at, vec2(0.0))) && all(lessThan(at, size)))) continue;
        ivec2 q = ivec2(at);
        float zq = texelFetch(u_depth, q, 0).r;
        if (zq <= 0.0) continue;  // sky occludes nothing
        vec3 front = view_position(vec2(q) + 0.5, size, zq) - centre;
        float distance = length(front);
        if (!(distance > 0.0) || distance > radius) continue;
        // A sample on or below the tangent plane occludes nothing. Testing that in 3D, not by
        // its angle in the slice, matters: snapped to a pixel centre, a sample leaves the
        // slice plane, and a point of the pixel's own plane can then map inside the
        // hemisphere. The tolerance, a sine of 1e-3, covers the RGBA16F normal's rounding.
        if (dot(front, normal) <= 1e-3 * distance) continue;
        vec3 back = front - view * thickness;  // the slab's far side, away from the eye
        // theta_f and theta_b from the view vector, positive on side 0 (towards +omega).
        float sign_side = side == 0 ? 1.0 : -1.0;
        float theta_f = sign_side * acos(clamp(dot(front, view) / distance, -1.0, 1.0));
        float theta_b = sign_side * acos(clamp(dot(safe_normalize(back), view), -1.0, 1.0));
        // Positions in the hemisphere, 0 at one side of the tangent plane, 1 at the other.
        float x_f = (theta_f - n) / kPi + 0.5, x_b = (theta_b - n) / kPi + 0.5;
        occluded |= sector_bits(min(x_f, x_b), max(x_f, x_b));
      }
    }
    // Total: cos n + n sin n, the slice's whole hemisphere; the projected normal's length
    // scales both so slices count by their share of the cosine lobe (GTAO eq. 8).
    float slice_total = cosine_measure(sector_angle(kSectors, n), n) -
                        cosine_measure(sector_angle(0, n), n);
    // No bit set subtracts exactly 0, so an open plane's ratio below is exactly 1.
    float slice_visible = slice_total - (occluded == 0u ? 0.0 : occluded_measure(occluded, n));
    visible += sl.projected_length * slice_visible;
    total += sl.projected_length * slice_total;
  }
  // total > 0 unless every slice was skipped; the ratio can pass 1 or 0 by rounding only.
  float visibility = total > 0.0 ? clamp(visible / total, 0.0, 1.0) : 1.0;
  visibility = pow(visibility, u_contrast);
  return clamp(1.0 - (1.0 - visibility) * u_intensity, 0.0, 1.0);
}

// GTAO's slice and step placement, shared by gtao.glsl and bitmask.glsl so the two techniques
// read the same depth samples per pixel and compare at equal cost.

const float kPi = 3.14159265;

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

// Distance of a step from the centre as a share of the screen radius: XeGTAO's power-2
// distribution (more samples near the centre), jittered per step, plus min_s so the first
// sample leaves the centre pixel.
float step_distance(float step_noise, int slice, int step, int steps, float min_s) {
  float jitter = fract(step_noise + float(slice + step * steps) * 0.6180339887);
  return pow((float(step) + jitter) / float(steps), 2.0) + min_s;
}

// One slice of the hemisphere around a pixel (GTAO, Jimenez et al. 2016, Algorithm 1 lines
// 6-13): its screen direction, and the pixel's normal projected into the slice plane.
struct Slice {
  vec2 omega;               // screen direction of the slice; rows run up as view-space y does
  float projected_length;   // |n_p|: the share of the cosine lobe the slice sees (eq. 8)
  float cos_n;              // cosine of the projected normal's angle from the view vector
  float n;                  // that angle, signed: positive towards +omega
};

// Slice `slice` of `slices`, rotated by the pixel's noise. False when the normal lies along the
// slice's axis: the slice then has no arc.
bool make_slice(int slice, int slices, float slice_noise, vec3 view, vec3 normal, out Slice s) {
  float phi = (float(slice) + slice_noise) / float(slices) * kPi;
  s.omega = vec2(cos(phi), sin(phi));
  vec3 direction = vec3(s.omega, 0.0);
  vec3 ortho_direction = direction - dot(direction, view) * view;
  vec3 axis = safe_normalize(cross(ortho_direction, view));
  vec3 projected_normal = normal - axis * dot(normal, axis);
  s.projected_length = length(projected_normal);
  if (s.projected_length < 1e-6) return false;
  float sign_n = dot(ortho_direction, projected_normal) >= 0.0 ? 1.0 : -1.0;
  s.cos_n = clamp(dot(projected_normal, view) / s.projected_length, 0.0, 1.0);
  s.n = sign_n * acos(s.cos_n);
  return true;
}

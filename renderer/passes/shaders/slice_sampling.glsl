// GTAO's slice and step placement, shared by gtao.glsl and bitmask.glsl so the two techniques
// read the same depth samples per pixel and compare at equal cost.

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

// Shared by every screen-space pass. Positions are view space, camera looking down -z;
// linear depth z = -position.z > 0, and z == 0 marks background (sky) pixels.
uniform vec2 u_ndc_to_view;  // (tan(fovy/2) * aspect, tan(fovy/2))

vec3 view_position(vec2 pixel_centre, vec2 size, float z) {
  vec2 ndc = pixel_centre / size * 2.0 - 1.0;
  return vec3(ndc * u_ndc_to_view * z, -z);
}

// normalize() of a zero vector is NaN on llvmpipe; this returns zero instead.
vec3 safe_normalize(vec3 v) { return v * inversesqrt(max(dot(v, v), 1e-30)); }

// The AlchemyAO/SAO per-pixel spin ((3x ^ y) + x*y), reduced to [0, 2pi) before any sin/cos:
// the raw value reaches 1e7 radians, where float sin/cos lose all accuracy.
float spin_angle(ivec2 p) {
  uint h = uint((3 * p.x) ^ p.y) + uint(p.x * p.y);
  return 6.2831853 * fract(float(h & 65535u) * (1.0 / 65536.0));
}

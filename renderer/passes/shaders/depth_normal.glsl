// The view normal at pixel p from the view positions around it, for a G-buffer without
// normals (SAO's depth-only estimator, the depth-only G-buffer). The includer defines
// vec3 position_at(ivec2 q, vec2 size): the view position of pixel q, vec3(0) on sky.
// Per axis the neighbour difference of smaller length (gl_ssao's "MinDiff"), so a depth edge
// on one side does not tilt the normal. On the image's border the one neighbour inside it
// decides: the clamped one is the pixel itself, a zero difference that would always win and
// leave no normal.
// The shorter of two differences, blended with the longer when their lengths are within a few
// per cent: a hard choice flips between two surfaces on a float rounding when the lengths tie
// (a thin feature, a pixel midway between two depths), which turned one pixel's AO by 0.2 when
// the same scene was scaled by 1e5. On a smooth surface the blend is the central difference.
vec3 softer_difference(vec3 a, vec3 b) {
  float aa = dot(a, a), bb = dot(b, b);
  float t = clamp(0.5 + 25.0 * (aa - bb) / max(aa + bb, 1e-30), 0.0, 1.0);
  return mix(a, b, t);
}

vec3 depth_normal(ivec2 p, vec3 c, vec2 size) {
  ivec2 hi = ivec2(size) - 1;
  vec3 r = position_at(min(p + ivec2(1, 0), hi), size) - c;
  vec3 l = c - position_at(max(p - ivec2(1, 0), ivec2(0)), size);
  vec3 t = position_at(min(p + ivec2(0, 1), hi), size) - c;
  vec3 b = c - position_at(max(p - ivec2(0, 1), ivec2(0)), size);
  vec3 dx = p.x == 0 ? r : p.x == hi.x ? l : softer_difference(r, l);
  vec3 dy = p.y == 0 ? t : p.y == hi.y ? b : softer_difference(t, b);
  vec3 n = safe_normalize(cross(dx, dy));
  return dot(n, -c) < 0.0 ? -n : n;
}

#version 450 core
#include "common.glsl"
in vec3 v_position;
in vec3 v_normal;
in vec3 v_colour;
layout(location = 0) out float o_depth;   // linear view depth, R32F
layout(location = 1) out vec4 o_normal;   // view-space unit normal, RGBA16F
layout(location = 2) out vec4 o_albedo;
void main() {
  vec3 n = safe_normalize(v_normal);
  // A degenerate vertex normal falls back to the face normal.
  if (dot(n, n) < 0.5) n = safe_normalize(cross(dFdx(v_position), dFdy(v_position)));
  // Two-sided: always face the camera, so back faces and cameras inside geometry behave.
  if (dot(n, -v_position) < 0.0) n = -n;
  o_depth = max(-v_position.z, 1e-30);
  o_normal = vec4(n, 0.0);
  o_albedo = vec4(v_colour, 1.0);
}

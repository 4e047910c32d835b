#version 450 core
// PMI's AO pass (pmi_pass.cpp): the G-buffer's transform, written as gbuffer.vert writes it so
// depths match, carrying each vertex's PMI visibility.
layout(location = 0) in vec3 a_position;  // world space
layout(location = 1) in float a_visibility;
uniform mat4 u_view;
uniform mat4 u_projection;
out float v_visibility;
void main() {
  vec4 p = u_view * vec4(a_position, 1.0);
  v_visibility = a_visibility;
  gl_Position = u_projection * p;
}

#version 450 core
layout(location = 0) in vec3 a_position;  // world space
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_colour;
uniform mat4 u_view;
uniform mat4 u_projection;
out vec3 v_position;  // view space
out vec3 v_normal;
out vec3 v_colour;
void main() {
  vec4 p = u_view * vec4(a_position, 1.0);
  v_position = p.xyz;
  v_normal = mat3(u_view) * a_normal;  // the view matrix is a rigid motion
  v_colour = a_colour;
  gl_Position = u_projection * p;
}

#version 450 core
// PMI item buffer: the object's polygons from one viewpoint (pmi_item_buffer.cpp).
layout(location = 0) in vec3 a_position;  // world space
uniform mat4 u_view_projection;
void main() { gl_Position = u_view_projection * vec4(a_position, 1.0); }

#version 450 core
// The depth-only G-buffer's second half: linear depth and a view normal per pixel from the
// reversed-Z depth buffer alone (XeGTAO reconstructs its normals so), written where the full
// G-buffer pass writes them. Reversed Z stores near / z, so z = near / stored; 0 is sky.
#include "common.glsl"
#include "pixel_main.glsl"
layout(r32f, binding = 0) writeonly uniform image2D u_depth_out;
layout(rgba16f, binding = 1) writeonly uniform image2D u_normal_out;
uniform sampler2D u_zbuffer;
uniform float u_near;

float linear_depth(ivec2 q) {
  float stored = texelFetch(u_zbuffer, q, 0).r;
  return stored > 0.0 ? u_near / stored : 0.0;
}
vec3 position_at(ivec2 q, vec2 size) {
  float z = linear_depth(q);
  return z > 0.0 ? view_position(vec2(q) + 0.5, size, z) : vec3(0.0);
}
#include "depth_normal.glsl"

void shade_pixel(ivec2 p) {
  ivec2 size = u_pixels;
  float z = linear_depth(p);
  vec3 n = z > 0.0 ? depth_normal(p, view_position(vec2(p) + 0.5, vec2(size), z), vec2(size))
                   : vec3(0.0);
  imageStore(u_depth_out, p, vec4(z));
  imageStore(u_normal_out, p, vec4(n, 0.0));
}

#version 450 core
// One level of SAO's depth pyramid from the level below: rotated-grid subsampling, never
// averaging (an average of two surfaces is a surface that does not exist).
layout(local_size_x = 8, local_size_y = 8) in;
#include "sao_pyramid.glsl"
uniform int u_level;  // 1..u_levels-1
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = level_size(u_level);
  if (any(greaterThanEqual(p, size))) return;
  ivec2 src = clamp(p * 2 + ivec2(p.y & 1, p.x & 1), ivec2(0), level_size(u_level - 1) - 1);
  pyramid[u_level_offset[u_level] + p.y * size.x + p.x] = pyramid_depth(src, u_level - 1);
}

#version 450 core
// The compute pipeline's MSSAO level: mssao_level.glsl per texel, stored into the level's RG32F
// result, or on the finest level into the R32F AO image. Writes need no format (GLSL 4.50), so
// one program serves both.
#include "common.glsl"
#include "mssao_level.glsl"
layout(local_size_x = PIXEL_GROUP, local_size_y = PIXEL_GROUP) in;
#include "dispatch_order.glsl"  // image_invocation
layout(binding = 0) writeonly uniform image2D u_level_out;
void main() {
  ivec2 p = image_invocation();
  if (any(greaterThanEqual(p, imageSize(u_level_out)))) return;
  imageStore(u_level_out, p, mssao_level(p));
}

#version 450 core
// The compute pipeline's MSSAO level: mssao_level.glsl per texel, stored into the level's RG32F
// result, or on the finest level into the R32F AO image. Writes need no format (GLSL 4.50), so
// one program serves both.
#include "common.glsl"
#include "mssao_level.glsl"
#include "dispatch_order.glsl"  // image_workgroup
#define PIXEL_WORKGROUP image_workgroup()
#include "pixel_main.glsl"
layout(binding = 0) writeonly uniform image2D u_level_out;
void shade_pixel(ivec2 p) { imageStore(u_level_out, p, mssao_level(p)); }

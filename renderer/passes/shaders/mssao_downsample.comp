#version 450 core
// The compute pipeline's MSSAO downsampling: mssao_downsample.glsl per coarse texel, stored
// into the level's depth and normal images that mssao_downsample.frag renders to.
#include "mssao_downsample.glsl"
#include "pixel_main.glsl"
layout(r32f, binding = 0) writeonly uniform image2D u_depth_out;
layout(rgba16f, binding = 1) writeonly uniform image2D u_normal_out;
void shade_pixel(ivec2 p) {
  vec4 texel = mssao_downsample(p);
  imageStore(u_depth_out, p, vec4(texel.x));
  imageStore(u_normal_out, p, vec4(texel.yzw, 0.0));
}

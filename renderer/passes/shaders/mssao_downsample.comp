#version 450 core
// The compute pipeline's MSSAO downsampling: mssao_downsample.glsl per coarse texel, stored
// into the level's depth and normal images that mssao_downsample.frag renders to.
#include "mssao_downsample.glsl"
layout(local_size_x = PIXEL_GROUP, local_size_y = PIXEL_GROUP) in;
layout(r32f, binding = 0) writeonly uniform image2D u_depth_out;
layout(rgba16f, binding = 1) writeonly uniform image2D u_normal_out;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_depth_out)))) return;
  vec4 texel = mssao_downsample(p);
  imageStore(u_depth_out, p, vec4(texel.x));
  imageStore(u_normal_out, p, vec4(texel.yzw, 0.0));
}

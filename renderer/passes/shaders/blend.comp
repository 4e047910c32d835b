#version 450 core
// The compute pipeline's blend: blend.glsl per pixel, stored into the three RGBA8 images that
// blend.frag's draw writes as render targets.
#include "blend.glsl"
#include "pixel_main.glsl"
layout(rgba8, binding = 0) writeonly uniform image2D u_no_ao_out;
layout(rgba8, binding = 1) writeonly uniform image2D u_with_ao_out;
layout(rgba8, binding = 2) writeonly uniform image2D u_ao_only_out;
void shade_pixel(ivec2 p) {
  vec4 no_ao, with_ao, ao_only;
  blend(p, no_ao, with_ao, ao_only);
  imageStore(u_no_ao_out, p, no_ao);
  imageStore(u_with_ao_out, p, with_ao);
  imageStore(u_ao_only_out, p, ao_only);
}

// The compute pipeline's AO entry point: the technique's estimate_ao (its .glsl, which the
// .frag twin includes too) at each pixel of the AO image, one invocation a pixel, the rows of
// workgroups in dispatch_order.glsl's order: a pixel's cost depends on what it sees (sky skips
// the taps, a near surface spans more pixels), so a thread given one band of the image would
// finish early. The dispatch covers whole workgroups, so invocations past the image's edge
// return before any tap. PIXEL_GROUP comes from make_pixel_program.
layout(local_size_x = PIXEL_GROUP, local_size_y = PIXEL_GROUP) in;
#include "dispatch_order.glsl"  // image_invocation
layout(r32f, binding = 0) writeonly uniform image2D u_ao_out;
void main() {
  ivec2 p = image_invocation();
  if (any(greaterThanEqual(p, imageSize(u_ao_out)))) return;
  imageStore(u_ao_out, p, vec4(estimate_ao(p)));
}

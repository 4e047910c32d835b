// The compute pipeline's AO entry point: the technique's estimate_ao (its .glsl, which the
// .frag twin includes too) at each pixel of the AO image, the rows of workgroups in
// dispatch_order.glsl's order: a pixel's cost depends on what it sees (sky skips the taps, a near
// surface spans more pixels), so a thread given one band of the image would finish early. One
// pixel an invocation (PIXEL_ROWS 1): at two, UE4's and GTAO's AO took longer on llvmpipe.
#include "dispatch_order.glsl"  // image_workgroup
#define PIXEL_WORKGROUP image_workgroup()
#include "pixel_main.glsl"
layout(r32f, binding = 0) writeonly uniform image2D u_ao_out;
void shade_pixel(ivec2 p) { imageStore(u_ao_out, p, vec4(estimate_ao(p))); }

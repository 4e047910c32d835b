// main() of a pixel program (make_pixel_program, dispatch_pixels): each invocation shades
// PIXEL_ROWS pixels (1 or 2) of one column, PIXEL_GROUP rows apart, so a workgroup covers
// PIXEL_GROUP x PIXEL_GROUP * PIXEL_ROWS pixels. Two cost less in a pass of a few
// instructions a pixel, where what each invocation costs before its first instruction is a large
// share (frame.hpp, light_pass_rows). The shader defines shade_pixel() and may define
// PIXEL_WORKGROUP (the image's workgroup this invocation shades; default its own). Pixels past
// the image's edge return first.
layout(local_size_x = PIXEL_GROUP, local_size_y = PIXEL_GROUP) in;
uniform ivec2 u_pixels;  // the image's size, set by dispatch_pixels
void shade_pixel(ivec2 p);
#ifndef PIXEL_WORKGROUP
#define PIXEL_WORKGROUP gl_WorkGroupID.xy
#endif
void main() {
  const uvec2 span = uvec2(PIXEL_GROUP, PIXEL_GROUP * PIXEL_ROWS);
  ivec2 p = ivec2(PIXEL_WORKGROUP * span + gl_LocalInvocationID.xy);
  if (any(greaterThanEqual(p, u_pixels))) return;
  shade_pixel(p);
#if PIXEL_ROWS == 2
  p.y += PIXEL_GROUP;
  if (p.y >= u_pixels.y) return;
  shade_pixel(p);
#endif
}

// The compute pipeline's AO entry point: the technique's estimate_ao (its .glsl, which the
// .frag twin includes too) at each pixel of the AO image, one invocation a pixel. The dispatch
// covers whole workgroups, so invocations past the image's edge return before any tap; sky
// pixels skip the taps inside estimate_ao. PIXEL_GROUP comes from make_pixel_program.
layout(local_size_x = PIXEL_GROUP, local_size_y = PIXEL_GROUP) in;
layout(r32f, binding = 0) writeonly uniform image2D u_ao_out;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_ao_out)))) return;
  imageStore(u_ao_out, p, vec4(estimate_ao(p)));
}

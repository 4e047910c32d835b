// The fragment pipeline's AO entry point: the technique's estimate_ao (its .glsl, which the
// .comp twin includes too) at each pixel the draw shades. draw_geometry_pixels's depth test has
// already left the sky out (cleared to 1, as estimate_ao would give it).
layout(location = 0) out float o_ao;
void main() { o_ao = estimate_ao(ivec2(gl_FragCoord.xy)); }

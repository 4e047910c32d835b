#version 450 core
// SAO's depth pyramid: rotated-grid subsampling, never averaging (an average of two
// surfaces is a surface that does not exist). Reads level i-1 (the texture's base level).
uniform sampler2D u_depth;
layout(location = 0) out float o_depth;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 src = clamp(p * 2 + ivec2(p.y & 1, p.x & 1), ivec2(0), textureSize(u_depth, 0) - 1);
  o_depth = texelFetch(u_depth, src, 0).r;
}

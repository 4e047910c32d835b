#version 450 core
#include "mssao_downsample.glsl"
layout(location = 0) out float o_depth;
layout(location = 1) out vec4 o_normal;
void main() {
  vec4 texel = mssao_downsample(ivec2(gl_FragCoord.xy));
  o_depth = texel.x;
  o_normal = vec4(texel.yzw, 0.0);
}

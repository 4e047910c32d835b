#version 450 core
#include "common.glsl"
#include "alchemy_estimator.glsl"
uniform sampler2D u_depth;
uniform sampler2D u_normal;
layout(location = 0) out float o_ao;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float z = texelFetch(u_depth, p, 0).r;
  if (z <= 0.0) { o_ao = 1.0; return; }
  o_ao = alchemy_ao(u_depth, p, z, safe_normalize(texelFetch(u_normal, p, 0).xyz));
}

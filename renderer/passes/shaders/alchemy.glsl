// Alchemy AO at one pixel of the G-buffer (alchemy_estimator.glsl, which MSSAO's levels share):
// estimate_ao for alchemy.frag and alchemy.comp.
#include "alchemy_estimator.glsl"
uniform sampler2D u_depth;
uniform sampler2D u_normal;
float estimate_ao(ivec2 p) {
  float z = texelFetch(u_depth, p, 0).r;
  if (z <= 0.0) return 1.0;
  return alchemy_ao(u_depth, p, z, safe_normalize(texelFetch(u_normal, p, 0).xyz));
}

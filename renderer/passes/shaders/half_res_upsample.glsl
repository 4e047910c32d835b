// The half-resolution AO brought back to the image's size (half_res_pass.hpp): estimate_ao at
// a geometry pixel is bilateral_upsample of the AO that the technique's pass wrote at half the
// width and height, over the half-size G-buffer it read; sky stays 1. Drawn or dispatched
// through ao_fragment.glsl or ao_compute.glsl, as the estimators are.
#include "bilateral_upsample.glsl"
uniform sampler2D u_depth;
uniform sampler2D u_normal;
uniform sampler2D u_half_ao;
uniform sampler2D u_half_depth;
uniform sampler2D u_half_normal;
float estimate_ao(ivec2 p) {
  float z = texelFetch(u_depth, p, 0).r;
  if (z <= 0.0) return 1.0;
  vec3 n = safe_normalize(texelFetch(u_normal, p, 0).xyz);
  return bilateral_upsample(u_half_ao, u_half_depth, u_half_normal, p, z, n, vec2(1.0)).x;
}

// Multi-Scale AO's G-buffer downsampling (Hoang & Low): of the four children sorted by
// depth, the average of the middle two when they span a small depth range, else the
// second nearest, so a coarse texel is always on a real surface. Sky children are left out.
uniform sampler2D u_depth;
uniform sampler2D u_normal;
// The relative depth span (a fraction of the nearest depth) under which the middle two are
// averaged.
const float kDepthThreshold = 0.05;
// The coarse texel p: its depth (0 on sky) in x, its normal in yzw.
vec4 mssao_downsample(ivec2 p) {
  ivec2 hi = textureSize(u_depth, 0) - 1;
  float z[4];
  vec3 n[4];
  int count = 0;
  for (int i = 0; i < 4; ++i) {
    ivec2 q = min(p * 2 + ivec2(i & 1, i >> 1), hi);
    float zq = texelFetch(u_depth, q, 0).r;
    if (zq <= 0.0) continue;
    // insertion sort by depth
    int j = count++;
    vec3 nq = texelFetch(u_normal, q, 0).xyz;
    while (j > 0 && z[j - 1] > zq) { z[j] = z[j - 1]; n[j] = n[j - 1]; --j; }
    z[j] = zq;
    n[j] = nq;
  }
  if (count == 0) return vec4(0.0);
  int lo = (count - 1) / 2, up = count / 2;  // the middle one or two
  if (z[count - 1] - z[0] <= kDepthThreshold * z[0]) {
    return vec4(0.5 * (z[lo] + z[up]), normalize(n[lo] + n[up] + vec3(0.0, 0.0, 1e-6)));
  }
  return vec4(z[lo], n[lo]);
}

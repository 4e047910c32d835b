// Hoang & Low's bilateral upsample from an image at half the width and height (MSSAO's levels,
// and the half-resolution AO of half_res_upsample.glsl): at fine pixel p, of depth z and normal
// n, the four coarse texels around it, each weighted bilinearly times its depth similarity
// (t_d 16) and normal similarity (t_n 8), so occlusion does not bleed across a depth edge or
// a crease. Coarse sky texels (depth 0) weigh nothing; `fallback` where all four are sky. The
// powers are squarings, not pow(): on llvmpipe pow is an exp2 and a log2, and the squarings
// took the 1080p half-resolution upsample from 42 to 32 ms.
vec2 bilateral_upsample(sampler2D coarse, sampler2D coarse_depth, sampler2D coarse_normal,
                        ivec2 p, float z, vec3 n, vec2 fallback) {
  ivec2 csize = textureSize(coarse, 0);
  vec2 cp = (vec2(p) + 0.5) * 0.5 - 0.5;
  ivec2 base = ivec2(floor(cp));
  vec2 f = cp - vec2(base);
  vec2 sum = vec2(0.0);
  float wsum = 0.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i & 1, i >> 1);
    ivec2 q = clamp(base + o, ivec2(0), csize - 1);
    float zq = texelFetch(coarse_depth, q, 0).r;
    if (zq <= 0.0) continue;
    float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    float wd = 1.0 / (1.0 + abs(zq - z) / z);
    wd *= wd, wd *= wd, wd *= wd, wd *= wd;
    float wn = max(0.0, (dot(texelFetch(coarse_normal, q, 0).xyz, n) + 1.0) * 0.5);
    wn *= wn, wn *= wn, wn *= wn;
    float w = bilinear * wd * wn + 1e-6;
    sum += w * texelFetch(coarse, q, 0).rg;
    wsum += w;
  }
  return wsum > 0.0 ? sum / wsum : fallback;
}

// SAO's depth pyramid, levels 0..u_levels-1 one after another in one buffer, each row by row.
// A buffer rather than a mipmapped texture: on llvmpipe a texelFetch with a per-pixel level
// cost several times a buffer load, and the AO pass makes thirteen per pixel.
layout(std430, binding = 0) buffer Pyramid { float pyramid[]; };
uniform int u_levels;
uniform int u_level_offset[6];  // where each level starts, in floats
uniform ivec2 u_size;           // level 0's

// SaoPass::size's rule. Arithmetic, not a uniform array: a per-pixel index into one cost
// a sixth of the AO pass on llvmpipe.
ivec2 level_size(int m) { return max(u_size >> m, ivec2(1)); }

float pyramid_depth(ivec2 q, int m) {
  return pyramid[u_level_offset[m] + q.y * level_size(m).x + q.x];
}

#version 450 core
// SAO's whole depth pyramid in one dispatch, one invocation per level-0 pixel. A level is the
// level below subsampled on a rotated grid, never averaged (an average of two surfaces is a
// surface that does not exist), so each texel of level m is one level-0 depth: follow the
// subsampling chain down to level 0 and copy that depth. No level waits for another, so there
// is no barrier between levels and no copy of level 0 through a pixel buffer: as a copy and
// five dispatches the pyramid took 0.32 ms of SAO's 0.39 on an H200 (bench/README.md).
layout(local_size_x = 8, local_size_y = 8) in;
#include "sao_pyramid.glsl"
uniform sampler2D u_depth;  // the G-buffer's linear depth: level 0
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  for (int m = 0; m < u_levels; ++m) {
    ivec2 size = level_size(m);
    if (any(greaterThanEqual(p, size))) return;  // each level is inside the one below
    ivec2 q = p;
    for (int k = m; k > 0; --k) {
      q = clamp(q * 2 + ivec2(q.y & 1, q.x & 1), ivec2(0), level_size(k - 1) - 1);
    }
    pyramid[u_level_offset[m] + p.y * size.x + p.x] = texelFetch(u_depth, q, 0).r;
  }
}

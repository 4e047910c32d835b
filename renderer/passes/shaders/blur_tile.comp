#version 450 core
// blur.glsl's axis for GPUs (the compute pipeline): one invocation per pixel. A workgroup's
// tile of pixels first loads its window (the tile widened by kRadius each way along the axis)
// into shared memory, so each tap is read from memory once per tile instead of 21 times, and
// the many short invocations hide the loads' latency, where blur.comp's long runs of eight
// left an H200 waiting (bench/README.md). The tile is a row segment for the first, horizontal,
// axis and eight columns for the second, so each load of a row is contiguous. The second axis
// stores straight into the AO texture (STORE_TEXTURE).
#ifdef SECOND_AXIS
layout(local_size_x = 8, local_size_y = 32) in;
const ivec2 kAxis = ivec2(0, 1);
#else
layout(local_size_x = 64, local_size_y = 1) in;
const ivec2 kAxis = ivec2(1, 0);
#endif
#include "blur.glsl"

const ivec2 kTile = ivec2(gl_WorkGroupSize.xy);
const ivec2 kWindowSize = kTile + 2 * kRadius * kAxis;
shared vec2 s_window[kWindowSize.x * kWindowSize.y];  // row by row

vec2 window_tap(int k) {
  ivec2 w = ivec2(gl_LocalInvocationID.xy) + k * kAxis;
  return s_window[w.y * kWindowSize.x + w.x];
}

void main() {
  ivec2 hi = u_size - 1;
  ivec2 window_origin = ivec2(gl_WorkGroupID.xy) * kTile - kRadius * kAxis;
  int group_index = int(gl_LocalInvocationIndex);
  for (int k = group_index; k < kWindowSize.x * kWindowSize.y; k += kTile.x * kTile.y) {
    ivec2 w = ivec2(k % kWindowSize.x, k / kWindowSize.x);
    s_window[k] = tap(clamp(window_origin + w, ivec2(0), hi));
  }
  memoryBarrierShared();
  barrier();
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (all(lessThanEqual(p, hi))) store(p, blurred_pair(0));
}

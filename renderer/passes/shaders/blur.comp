#version 450 core
// blur.glsl's axis for a CPU rasteriser (llvmpipe): each invocation blurs kRun consecutive
// pixels along the axis from one window of kRun + 2 kRadius taps, so a pixel costs 3.5 loads
// instead of 21: on llvmpipe a load was most of a tap's cost, and the blur half of the 1080p
// SAO frame. RUN and GROUP come from blur_pass.cpp.
layout(local_size_x = GROUP, local_size_y = GROUP) in;
#include "blur.glsl"

const int kRun = RUN;
#if RUN != 8
#error "main() blurs eight pixels per invocation"
#endif
const int kWindow = kRun + 2 * kRadius;
vec2 window[kWindow];
vec2 window_tap(int k) { return window[k]; }

void blur_pixel(ivec2 first, int j, int last) {
  ivec2 p = first + j * u_axis;
  if (along(p) <= last) store(p, blurred_pair(j));
}

void main() {
  ivec2 hi = u_size - 1;
  ivec2 across = ivec2(1) - u_axis;
  // Invocation (x, y) of the horizontal axis runs pixels (kRun x .. kRun x + kRun - 1, y).
  ivec2 first = ivec2(gl_GlobalInvocationID.xy) * (u_axis * kRun + across);
  int last = along(hi);
  if (any(greaterThan(first, hi))) return;
  for (int j = 0; j < kWindow; ++j) {
    window[j] = tap(clamp(first + (j - kRadius) * u_axis, ivec2(0), hi));
  }
  // Unrolled by hand so that every window index is a constant: with a loop over j the window
  // stayed an array indexed at run time, which doubled the pass's time on llvmpipe.
  blur_pixel(first, 0, last);
  blur_pixel(first, 1, last);
  blur_pixel(first, 2, last);
  blur_pixel(first, 3, last);
  blur_pixel(first, 4, last);
  blur_pixel(first, 5, last);
  blur_pixel(first, 6, last);
  blur_pixel(first, 7, last);
}

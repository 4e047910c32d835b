// Two views of a change that a reviewer reads a small one from, where Resemble's diff marks
// every changed pixel alike and a FLIP map of a 2 % change is nearly black:
// - absolute: |actual - expected| per channel, scaled so the largest difference is white
//   (OpenImageIO idiff's -abs -scale);
// - signed: the mean of the channels' actual - expected, in a diverging map (blue: darker,
//   white: unchanged, red: brighter), scaled to the largest such mean.
#pragma once

#include "image/rgba_image.hpp"

namespace aosuite::comparison {

struct DifferenceViews {
  RgbaImage absolute, signed_change;
  int largest_channel = 0;    // the absolute view's white, in levels (0: no difference)
  double largest_signed = 0;  // the signed view's full colour, in levels
};

// Both views of two 8-bit images of one size (alpha ignored; the views are opaque).
DifferenceViews difference_views(RgbaView expected, RgbaView actual);

}  // namespace aosuite::comparison

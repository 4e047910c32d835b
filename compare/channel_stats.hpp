// The per-sample figures of two 8-bit RGBA images of one size that Resemble's count does not
// give: the largest channel difference and where it is, how many pixels differ at all, and the
// mean signed and absolute differences. Resemble's `less` mode ignores up to 16 levels a
// channel; these are what catch a global change below that (a frame 2 % brighter moves every
// sample by about 5 levels: mean shift 5, no Resemble mismatch).
#pragma once

#include <array>
#include <cstdint>

namespace aosuite::comparison {

struct ChannelStats {
  int max_delta = 0;            // largest |actual - expected| of any R, G, B or A sample
  std::int64_t at = -1;         // the first pixel (row-major index) holding it; -1: none differs
  std::uint64_t differing = 0;  // pixels with any channel changed
  std::uint64_t pixels = 0;     // pixels counted
  std::array<std::int64_t, 4> sum_signed{};  // per channel, sum of actual - expected
  std::uint64_t sum_abs = 0;                 // over every sample, sum of |actual - expected|

  // Adds `count` pixels of packed RGBA8 images, `first` the row-major index of the first.
  void add(const unsigned char* expected, const unsigned char* actual, std::uint64_t count,
           std::uint64_t first);
  void merge(const ChannelStats& s);
  // The largest |mean signed difference| of any channel, in levels (0 when nothing counted):
  // a global shift of brightness or colour.
  double mean_shift() const;
  // The mean |difference| of every sample, in levels: noise that shifts nothing on average.
  double mean_delta() const;
};

}  // namespace aosuite::comparison

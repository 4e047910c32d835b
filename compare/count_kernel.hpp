// The hot loop of the common case (no diff image, no antialiasing, no areas): count the
// pixels whose channel difference reaches a per-channel threshold and bound them.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

namespace aosuite {

// A count of mismatching pixels and their bounding box; every comparison path tallies
// into one of these, per thread, and merges them.
struct MismatchTally {
  std::uint64_t count = 0;
  int top = 0, left = 0, bottom = 0, right = 0;  // valid when count > 0

  // n mismatches on row y, the first at column `first` and the last at `last`.
  void add(int y, std::uint64_t n, int first, int last) {
    if (n == 0) return;
    merge({n, y, first, y, last});
  }
  void merge(const MismatchTally& t) {
    if (t.count == 0) return;
    if (count == 0) {
      *this = t;
      return;
    }
    count += t.count;
    top = std::min(top, t.top);
    bottom = std::max(bottom, t.bottom);
    left = std::min(left, t.left);
    right = std::max(right, t.right);
  }
};

// a and b are tightly packed RGBA8 images of width x height. A pixel mismatches when, for
// some channel c, |a_c - b_c| >= min_delta[c]; min_delta in [1, 256] (256: never).
MismatchTally count_mismatches(const unsigned char* a, const unsigned char* b, int width,
                               int height, const std::array<int, 4>& min_delta);

// The same on one thread for `rows` rows that are rows first_row.. of their images: a and b
// point at the band's first row.
MismatchTally count_band(const unsigned char* a, const unsigned char* b, int width, int rows,
                         int first_row, const std::array<int, 4>& min_delta);

// Plain per-pixel reference of the same function, for tests and benchmarks.
MismatchTally count_mismatches_scalar(const unsigned char* a, const unsigned char* b, int width,
                                      int height, const std::array<int, 4>& min_delta);

}  // namespace aosuite

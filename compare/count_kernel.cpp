#include "compare/count_kernel.hpp"

#include <algorithm>
#include <cstring>
#include <mutex>
#include <opencv2/core/utility.hpp>

namespace aosuite {
namespace {

using u8x64 = unsigned char __attribute__((vector_size(64)));
using u32x16 = std::uint32_t __attribute__((vector_size(64)));
using i32x16 = std::int32_t __attribute__((vector_size(64)));

bool pixel_differs(const unsigned char* a, const unsigned char* b, const int* min_delta) {
  for (int c = 0; c < 4; ++c) {
    if (std::abs(int{a[c]} - int{b[c]}) >= min_delta[c]) return true;
  }
  return false;
}

void merge_row(MismatchTally& t, int y, std::uint64_t n, int first, int last) {
  if (n == 0) return;
  if (t.count == 0) {
    t = {n, y, first, y, last};
    return;
  }
  t.count += n;
  t.top = std::min(t.top, y);
  t.bottom = std::max(t.bottom, y);
  t.left = std::min(t.left, first);
  t.right = std::max(t.right, last);
}

void merge(MismatchTally& into, const MismatchTally& t) {
  if (t.count == 0) return;
  if (into.count == 0) {
    into = t;
    return;
  }
  into.count += t.count;
  into.top = std::min(into.top, t.top);
  into.bottom = std::max(into.bottom, t.bottom);
  into.left = std::min(into.left, t.left);
  into.right = std::max(into.right, t.right);
}

// Counts a row's mismatching pixels 16 at a time. AVX2 and baseline SSE2 clones are built;
// the loader picks one for the machine.
__attribute__((target_clones("avx2", "default"))) std::uint64_t count_row(const unsigned char* a,
                                                                          const unsigned char* b,
                                                                          int width,
                                                                          const int* min_delta) {
  u8x64 thr;  // delta - 1 per channel: d > thr means mismatch; 255 can never be exceeded
  for (int i = 0; i < 64; ++i) {
    thr[i] = static_cast<unsigned char>(std::min(min_delta[i % 4], 256) - 1);
  }
  i32x16 acc = {};
  int x = 0;
  for (; x + 16 <= width; x += 16) {
    u8x64 va, vb;
    std::memcpy(&va, a + 4 * x, 64);
    std::memcpy(&vb, b + 4 * x, 64);
    const u8x64 d = (va > vb) ? va - vb : vb - va;
    const u8x64 over = reinterpret_cast<u8x64>(d > thr);
    u32x16 lanes;
    std::memcpy(&lanes, &over, 64);
    acc -= reinterpret_cast<i32x16>(lanes != 0);  // -1 per mismatching pixel
  }
  std::uint64_t n = 0;
  for (int i = 0; i < 16; ++i) n += static_cast<std::uint32_t>(acc[i]);
  for (; x < width; ++x) n += pixel_differs(a + 4 * x, b + 4 * x, min_delta);
  return n;
}

MismatchTally count_rows(const unsigned char* a, const unsigned char* b, int width, int y0, int y1,
                         const int* min_delta) {
  MismatchTally t;
  const std::size_t stride = std::size_t(width) * 4;
  for (int y = y0; y < y1; ++y) {
    const unsigned char* ra = a + y * stride;
    const unsigned char* rb = b + y * stride;
    const std::uint64_t n = count_row(ra, rb, width, min_delta);
    if (n == 0) continue;
    // Only a pixel left of the current left bound (or right of the right one) can move it,
    // so these scans stop early once the bounds have spread.
    int first = 0, last = width - 1;
    const int left_limit = t.count ? t.left : width;
    while (first < left_limit && !pixel_differs(ra + 4 * first, rb + 4 * first, min_delta)) {
      ++first;
    }
    const int right_limit = t.count ? t.right : -1;
    while (last > right_limit && !pixel_differs(ra + 4 * last, rb + 4 * last, min_delta)) {
      --last;
    }
    merge_row(t, y, n, first, last);
  }
  return t;
}

}  // namespace

MismatchTally count_mismatches(const unsigned char* a, const unsigned char* b, int width,
                               int height, const std::array<int, 4>& min_delta) {
  MismatchTally total;
  std::mutex m;
  const double pixels = double(width) * height;
  cv::parallel_for_(
      cv::Range(0, height),
      [&](const cv::Range& r) {
        const MismatchTally t = count_rows(a, b, width, r.start, r.end, min_delta.data());
        std::lock_guard lock(m);
        merge(total, t);
      },
      std::max(1.0, pixels / (1 << 18)));
  return total;
}

MismatchTally count_mismatches_scalar(const unsigned char* a, const unsigned char* b, int width,
                                      int height, const std::array<int, 4>& min_delta) {
  MismatchTally t;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t off = (std::size_t(y) * width + x) * 4;
      if (pixel_differs(a + off, b + off, min_delta.data())) merge_row(t, y, 1, x, x);
    }
  }
  return t;
}

}  // namespace aosuite

#include "compare/count_kernel.hpp"

#include <emmintrin.h>

#include <algorithm>
#include <cstring>
#include <mutex>

#include "compare/parallel_rows.hpp"

namespace aosuite {
namespace {

bool pixel_differs(const unsigned char* a, const unsigned char* b, const int* min_delta) {
  for (int c = 0; c < 4; ++c) {
    if (std::abs(int{a[c]} - int{b[c]}) >= min_delta[c]) return true;
  }
  return false;
}

struct RowTally {
  std::uint64_t count = 0;
  int first = -1, last = -1;  // first and last mismatching pixel
};

// Counts a row's mismatching pixels 16 at a time and finds the first and last of them.
// SSE2 is x86-64's baseline, so this needs no dispatch; one core of the CI machine already
// moves more pixels per second this way than the PNG decoder can produce.
RowTally count_row(const unsigned char* a, const unsigned char* b, int width,
                   const int* min_delta) {
  // d > delta - 1 per channel means mismatch; saturating d - (delta - 1) is then non-zero.
  // A delta of 256 can never be reached: its lane is masked off.
  alignas(16) unsigned char thr[16], keep[16];
  for (int i = 0; i < 16; ++i) {
    thr[i] = static_cast<unsigned char>(std::min(min_delta[i % 4], 255) - 1);
    keep[i] = min_delta[i % 4] > 255 ? 0 : 0xff;
  }
  const __m128i vthr = _mm_load_si128(reinterpret_cast<const __m128i*>(thr));
  const __m128i vkeep = _mm_load_si128(reinterpret_cast<const __m128i*>(keep));
  const __m128i zero = _mm_setzero_si128();
  // -1 per pixel lane that matches, four pixels at a time
  auto matches = [&](int x) {
    const __m128i va = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + 4 * x));
    const __m128i vb = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + 4 * x));
    const __m128i d = _mm_sub_epi8(_mm_max_epu8(va, vb), _mm_min_epu8(va, vb));
    return _mm_cmpeq_epi32(_mm_and_si128(_mm_subs_epu8(d, vthr), vkeep), zero);
  };
  __m128i acc = zero;
  int first_block = -1, last_block = -1;
  int x = 0;
  for (; x + 16 <= width; x += 16) {
    const __m128i m0 = matches(x), m1 = matches(x + 4), m2 = matches(x + 8), m3 = matches(x + 12);
    const __m128i all = _mm_and_si128(_mm_and_si128(m0, m1), _mm_and_si128(m2, m3));
    if (_mm_movemask_epi8(all) != 0xffff) {
      acc = _mm_add_epi32(acc, _mm_add_epi32(_mm_add_epi32(m0, m1), _mm_add_epi32(m2, m3)));
      acc = _mm_add_epi32(acc, _mm_set1_epi32(4));  // 16 pixels, minus the matching ones
      if (first_block < 0) first_block = x;
      last_block = x;
    }
  }
  alignas(16) std::int32_t lanes[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(lanes), acc);
  RowTally t;
  t.count = std::uint64_t(lanes[0]) + lanes[1] + lanes[2] + lanes[3];
  // Exact positions inside the first and last blocks, and the scalar tail.
  if (first_block >= 0) {
    t.first = first_block;
    while (!pixel_differs(a + 4 * t.first, b + 4 * t.first, min_delta)) ++t.first;
    t.last = last_block + 15;
    while (!pixel_differs(a + 4 * t.last, b + 4 * t.last, min_delta)) --t.last;
  }
  for (; x < width; ++x) {
    if (!pixel_differs(a + 4 * x, b + 4 * x, min_delta)) continue;
    ++t.count;
    if (t.first < 0) t.first = x;
    t.last = x;
  }
  return t;
}

}  // namespace

MismatchTally count_band(const unsigned char* a, const unsigned char* b, int width, int rows,
                         int first_row, const std::array<int, 4>& min_delta) {
  MismatchTally t;
  const std::size_t stride = std::size_t(width) * 4;
  for (int y = 0; y < rows; ++y) {
    const RowTally r = count_row(a + y * stride, b + y * stride, width, min_delta.data());
    t.add(first_row + y, r.count, r.first, r.last);
  }
  return t;
}

MismatchTally count_mismatches(const unsigned char* a, const unsigned char* b, int width,
                               int height, const std::array<int, 4>& min_delta) {
  MismatchTally total;
  std::mutex m;
  parallel_rows(width, height, [&](int y0, int y1) {
    const std::size_t offset = std::size_t(y0) * std::size_t(width) * 4;
    const MismatchTally t = count_band(a + offset, b + offset, width, y1 - y0, y0, min_delta);
    std::lock_guard lock(m);
    total.merge(t);
  });
  return total;
}

MismatchTally count_mismatches_scalar(const unsigned char* a, const unsigned char* b, int width,
                                      int height, const std::array<int, 4>& min_delta) {
  MismatchTally t;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t off = (std::size_t(y) * width + x) * 4;
      if (pixel_differs(a + off, b + off, min_delta.data())) t.add(y, 1, x, x);
    }
  }
  return t;
}

}  // namespace aosuite

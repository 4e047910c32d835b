#include "image/png_unfilter_quad.hpp"

#include <immintrin.h>

#include <cstdint>
#include <cstring>

namespace aosuite {
namespace {

#define AOSUITE_AVX2 __attribute__((target("avx2"), always_inline)) inline

// Row k runs kLag pixels behind row k - 1, so the pixel above a lane's next pixel was made
// kLag steps before: moving it into the lane (a cross-lane permute of several cycles) is
// then off the chain from each pixel to the next, which alone sets the pace.
constexpr int kLag = 2;
constexpr int kRows = 4;
// Steps until the last lane has started (it starts on the last of them), and after the
// first lane has ended.
constexpr int kLeadIn = kLag * (kRows - 1) + 1, kLeadOut = kLag * (kRows - 1);
static_assert(kQuadMinPixels > kLeadIn);

// All-ones in each lane whose row has the given filter type.
AOSUITE_AVX2 __m256i lanes_of(const unsigned char* raw, std::size_t stride, int type) {
  alignas(32) std::int64_t mask[kRows];
  for (int k = 0; k < kRows; ++k) mask[k] = raw[k * stride] == type ? -1 : 0;
  return _mm256_load_si256(reinterpret_cast<const __m256i*>(mask));
}

AOSUITE_AVX2 __m256i widen_pixel(const unsigned char* p) {
  std::int32_t v;
  std::memcpy(&v, p, 4);
  return _mm256_cvtepu8_epi16(_mm_cvtsi32_si128(v));
}

// The four rows' state between steps, in 16-bit lanes whose high bytes stay zero (sums are
// taken modulo 256 with paddb), as in png_unfilter.cpp's one-row steps.
template <bool kPaeth>
struct Quad {
  __m256i sub, up, avg, paeth;                  // which lanes have which filter (None: none)
  __m256i made[kLag] = {};                      // the last kLag steps' pixels, newest first
  __m256i above_left = _mm256_setzero_si256();  // the last step's pixels above (c)

  // One pixel of each row from its filtered bytes, given the row above row 0's pixel.
  // `fresh` marks lanes starting their row: nothing to their left or above-left.
  AOSUITE_AVX2 __m256i step(__m256i filtered, __m256i above0, __m256i fresh) {
    // Above lane k is what lane k - 1 made kLag steps ago; above lane 0, the row above.
    const __m256i above = _mm256_blend_epi32(
        _mm256_permute4x64_epi64(made[kLag - 1], _MM_SHUFFLE(2, 1, 0, 0)), above0, 0x03);
    const __m256i a = _mm256_andnot_si256(fresh, made[0]), b = above;
    const __m256i c = _mm256_andnot_si256(fresh, above_left);
    // Predictors that need no a first (Up; None is zero), then Sub and Average, then Paeth
    // last, as the longest chain.
    __m256i pred = _mm256_and_si256(up, b);
    pred = _mm256_blendv_epi8(pred, a, sub);
    pred = _mm256_blendv_epi8(pred, _mm256_srli_epi16(_mm256_add_epi16(a, b), 1), avg);
    if constexpr (kPaeth) {
      // As Paeth4 in png_unfilter.cpp: only x = a - c depends on the pixel to the left.
      const __m256i q = _mm256_sub_epi16(b, c);
      const __m256i pa = _mm256_abs_epi16(q);
      const __m256i x = _mm256_sub_epi16(a, c);
      const __m256i pb = _mm256_abs_epi16(x);
      const __m256i pc = _mm256_abs_epi16(_mm256_add_epi16(x, q));
      const __m256i not_a = _mm256_cmpgt_epi16(pa, _mm256_min_epi16(pb, pc));
      const __m256i b_or_c = _mm256_blendv_epi8(b, c, _mm256_cmpgt_epi16(pb, pc));
      pred = _mm256_blendv_epi8(pred, _mm256_blendv_epi8(a, b_or_c, not_a), paeth);
    }
    const __m256i out = _mm256_add_epi8(filtered, pred);
    for (int i = kLag - 1; i > 0; --i) made[i] = made[i - 1];
    made[0] = out;
    above_left = above;
    return out;
  }
};

// Step t's pixels as bytes, lane k's in dword k.
AOSUITE_AVX2 __m128i narrow(__m256i v) {
  const __m256i packed = _mm256_packus_epi16(v, v);  // per 128 bits: lanes 0 1 0 1, 2 3 2 3
  return _mm_unpacklo_epi64(_mm256_castsi256_si128(packed), _mm256_extracti128_si256(packed, 1));
}

// Four rows being unfiltered: at step t lane k is at pixel t - kLag * k, its filtered bytes
// at src + 4t + k * from and its output at out + 4t + k * to.
template <bool kPaeth>
struct QuadRows {
  Quad<kPaeth> q;
  const unsigned char* src;
  unsigned char* out;
  const unsigned char* prev;
  int w, from, to;

  AOSUITE_AVX2 __m128i step(int t, __m256i fresh) {
    const unsigned char* p = src + 4 * t;
    std::int32_t v[kRows];
    for (int k = 0; k < kRows; ++k) std::memcpy(&v[k], p + k * from, 4);
    const __m256i filtered = _mm256_cvtepu8_epi16(_mm_setr_epi32(v[0], v[1], v[2], v[3]));
    return narrow(q.step(filtered, widen_pixel(prev + 4 * (t < w ? t : w - 1)), fresh));
  }
  // The lead-in and lead-out (and the steps left over from blocks): lanes before their row's
  // start or past its end run on bytes of the neighbouring rows (inside the four rows given)
  // and are not stored.
  AOSUITE_AVX2 void ramp_step(int t) {
    alignas(32) std::int64_t fresh[kRows];
    for (int k = 0; k < kRows; ++k) fresh[k] = t == kLag * k ? -1 : 0;
    alignas(16) std::int32_t px[kRows];
    _mm_store_si128(reinterpret_cast<__m128i*>(px),
                    step(t, _mm256_load_si256(reinterpret_cast<const __m256i*>(fresh))));
    for (int k = 0; k < kRows; ++k) {
      const int x = t - kLag * k;
      if (x >= 0 && x < w) std::memcpy(out + 4 * t + k * to, &px[k], 4);
    }
  }
  // Four steps from t on, all lanes inside their rows: each row's four pixels are one
  // 16-byte load and store, turned into steps and back by a 4 x 4 transpose of dwords.
  AOSUITE_AVX2 void block(int t) {
    __m128i v[kRows];
    for (int k = 0; k < kRows; ++k) {
      v[k] = _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + 4 * t + k * from));
    }
    transpose(v);
    const __m128i above = _mm_loadu_si128(reinterpret_cast<const __m128i*>(prev + 4 * t));
    const __m256i none_fresh = _mm256_setzero_si256();
    const __m256i m0 = q.step(_mm256_cvtepu8_epi16(v[0]), _mm256_cvtepu8_epi16(above), none_fresh);
    const __m256i m1 = q.step(_mm256_cvtepu8_epi16(v[1]),
                              _mm256_cvtepu8_epi16(_mm_srli_si128(above, 4)), none_fresh);
    const __m256i m2 = q.step(_mm256_cvtepu8_epi16(v[2]),
                              _mm256_cvtepu8_epi16(_mm_srli_si128(above, 8)), none_fresh);
    const __m256i m3 = q.step(_mm256_cvtepu8_epi16(v[3]),
                              _mm256_cvtepu8_epi16(_mm_srli_si128(above, 12)), none_fresh);
    // Per 128 bits, steps 0 and 1 (2 and 3) of rows 0 and 1, then of rows 2 and 3, as bytes:
    // picking every other dword gives rows 0 and 2, the others rows 1 and 3.
    const __m256 p01 = _mm256_castsi256_ps(_mm256_packus_epi16(m0, m1));
    const __m256 p23 = _mm256_castsi256_ps(_mm256_packus_epi16(m2, m3));
    const __m256i rows02 = _mm256_castps_si256(_mm256_shuffle_ps(p01, p23, 0x88));
    const __m256i rows13 = _mm256_castps_si256(_mm256_shuffle_ps(p01, p23, 0xdd));
    const auto store = [&](int k, __m128i px) {
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 4 * t + k * to), px);
    };
    store(0, _mm256_castsi256_si128(rows02));
    store(1, _mm256_castsi256_si128(rows13));
    store(2, _mm256_extracti128_si256(rows02, 1));
    store(3, _mm256_extracti128_si256(rows13, 1));
  }
  // Rows of dwords to columns: v[i]'s dword j becomes v[j]'s dword i.
  AOSUITE_AVX2 static void transpose(__m128i (&v)[kRows]) {
    const __m128i t0 = _mm_unpacklo_epi32(v[0], v[1]), t1 = _mm_unpacklo_epi32(v[2], v[3]);
    const __m128i t2 = _mm_unpackhi_epi32(v[0], v[1]), t3 = _mm_unpackhi_epi32(v[2], v[3]);
    v[0] = _mm_unpacklo_epi64(t0, t1);
    v[1] = _mm_unpackhi_epi64(t0, t1);
    v[2] = _mm_unpacklo_epi64(t2, t3);
    v[3] = _mm_unpackhi_epi64(t2, t3);
  }
};

template <bool kPaeth>
__attribute__((target("avx2"))) void quad(const unsigned char* raw, unsigned char* out,
                                          const unsigned char* prev, std::size_t len) {
  const std::size_t stride = len + 1;
  const int from = static_cast<int>(stride) - 4 * kLag;
  QuadRows<kPaeth> rows{{lanes_of(raw, stride, 1), lanes_of(raw, stride, 2),
                         lanes_of(raw, stride, 3), lanes_of(raw, stride, 4)},
                        raw + 1,
                        out,
                        prev,
                        static_cast<int>(len / 4),
                        from,
                        static_cast<int>(len) - 4 * kLag};
  const int w = rows.w;
  for (int t = 0; t < kLeadIn; ++t) rows.ramp_step(t);
  int t = kLeadIn;
  for (; t + 4 <= w; t += 4) rows.block(t);
  for (; t < w + kLeadOut; ++t) rows.ramp_step(t);
}

#undef AOSUITE_AVX2

}  // namespace

bool quad_unfilter_supported() {
  static const bool yes = __builtin_cpu_supports("avx2");
  return yes;
}

void unfilter_quad(const unsigned char* raw, unsigned char* out, const unsigned char* prev,
                   std::size_t len) {
  const std::size_t stride = len + 1;
  bool paeth = false;
  for (int k = 0; k < kRows; ++k) paeth |= raw[k * stride] == 4;
  (paeth ? quad<true> : quad<false>)(raw, out, prev, len);
}

}  // namespace aosuite

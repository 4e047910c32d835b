#include "image/png_unfilter.hpp"

#include <immintrin.h>

#include <cstdlib>
#include <cstring>

#include "image/png_unfilter_quad.hpp"

namespace aosuite {
namespace {

int paeth(int a, int b, int c) {
  const int p = a + b - c;
  const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

// A byte at a time, for RGB rows and CPUs without SSE4.1; `predict` gives a byte's
// predictor from the bytes left (a), above (b) and above-left (c) of it.
template <int Bpp, class Predict>
void unfilter_scalar(const unsigned char* src, unsigned char* dst, const unsigned char* prev,
                     std::size_t len, Predict predict) {
  for (std::size_t i = 0; i < len; ++i) {
    const int a = i < Bpp ? 0 : dst[i - Bpp], c = i < Bpp ? 0 : prev[i - Bpp];
    dst[i] = static_cast<unsigned char>(src[i] + predict(a, prev[i], c));
  }
}

template <int Bpp>
void unfilter_scalar(int type, const unsigned char* src, unsigned char* dst,
                     const unsigned char* prev, std::size_t len) {
  switch (type) {
    case 1:
      return unfilter_scalar<Bpp>(src, dst, prev, len, [](int a, int, int) { return a; });
    case 3:
      return unfilter_scalar<Bpp>(src, dst, prev, len,
                                  [](int a, int b, int) { return (a + b) >> 1; });
    default:
      return unfilter_scalar<Bpp>(src, dst, prev, len, paeth);
  }
}

std::int32_t load32(const unsigned char* p) {
  std::int32_t v;
  std::memcpy(&v, p, 4);
  return v;
}

void store32(unsigned char* p, __m128i v) {
  const std::int32_t out = _mm_cvtsi128_si32(v);
  std::memcpy(p, &out, 4);
}

// Up, 16 bytes at a time. Written out because dst may overlap src, which keeps the
// compiler from vectorising the plain loop.
void unup(const unsigned char* src, unsigned char* dst, const unsigned char* prev,
          std::size_t len) {
  std::size_t i = 0;
  for (; i + 16 <= len; i += 16) {
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + i));
    const __m128i p = _mm_loadu_si128(reinterpret_cast<const __m128i*>(prev + i));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + i), _mm_add_epi8(v, p));
  }
  for (; i < len; ++i) dst[i] = static_cast<unsigned char>(src[i] + prev[i]);
}

// A pixel's bytes in 16-bit lanes. Sums of such lanes are taken modulo 256 with paddb,
// which leaves the high bytes zero: no masking on the chain.
__m128i widen(const unsigned char* p) {
  return _mm_unpacklo_epi8(_mm_cvtsi32_si128(load32(p)), _mm_setzero_si128());
}

// Sub, Average and Paeth for 4-byte pixels, a pixel per step in SIMD lanes. Each pixel
// depends on the one to its left, so a step's latency is what counts (the scalar loops went
// a byte at a time with a branch per byte); each filter keeps what it needs of that pixel.
#define AOSUITE_SSE41 __attribute__((target("sse4.1"), always_inline)) inline

// Sub: the left pixel added bytewise.
struct Sub4 {
  __m128i a = _mm_setzero_si128();
  AOSUITE_SSE41 void step(const unsigned char* src, const unsigned char*, unsigned char* dst) {
    a = _mm_add_epi8(_mm_cvtsi32_si128(load32(src)), a);
    store32(dst, a);
  }
};

// Average in 16-bit lanes, where (a + b) >> 1 is exact: three dependent instructions a pixel
// where the bytewise mean (pavgb less the low bit of a ^ b) took four.
struct Avg4 {
  __m128i a = _mm_setzero_si128();
  AOSUITE_SSE41 void step(const unsigned char* src, const unsigned char* above,
                          unsigned char* dst) {
    const __m128i mean = _mm_srli_epi16(_mm_add_epi16(a, widen(above)), 1);
    a = _mm_add_epi8(widen(src), mean);
    store32(dst, _mm_packus_epi16(a, a));
  }
};

// Paeth in 16-bit lanes. Only x = a - c depends on the previous pixel; b - c and
// pa = |b - c| are computed off that chain, which SSSE3's pabsw and SSE4.1's pblendvb keep
// short (7 dependent instructions a pixel against 13 in SSE2).
struct Paeth4 {
  __m128i a = _mm_setzero_si128(), c = _mm_setzero_si128();
  AOSUITE_SSE41 void step(const unsigned char* src, const unsigned char* above,
                          unsigned char* dst) {
    const __m128i b = widen(above);
    const __m128i q = _mm_sub_epi16(b, c);
    const __m128i pa = _mm_abs_epi16(q);  // |p - a| with p = a + b - c
    const __m128i x = _mm_sub_epi16(a, c);
    const __m128i pb = _mm_abs_epi16(x);
    const __m128i pc = _mm_abs_epi16(_mm_add_epi16(x, q));
    const __m128i not_a = _mm_cmpgt_epi16(pa, _mm_min_epi16(pb, pc));
    const __m128i b_or_c = _mm_blendv_epi8(b, c, _mm_cmpgt_epi16(pb, pc));
    a = _mm_add_epi8(widen(src), _mm_blendv_epi8(a, b_or_c, not_a));
    store32(dst, _mm_packus_epi16(a, a));
    c = b;
  }
};

#undef AOSUITE_SSE41

template <class Filter>
__attribute__((target("sse4.1"))) void row4(const unsigned char* src, unsigned char* dst,
                                            const unsigned char* prev, std::size_t len) {
  Filter f;
  for (std::size_t i = 0; i < len; i += 4) f.step(src + i, prev + i, dst + i);
}

// Two rows at once, the second a pixel behind the first, so that the pixels above it are
// written: two independent chains a step, which the core overlaps (per row and pixel, in TSC
// ticks on the project's VM: Paeth 9.1 alone, 4.8 in pairs; Average 3.8 and 1.9).
template <class First, class Second>
__attribute__((target("sse4.1"))) void pair4(const unsigned char* src, unsigned char* dst,
                                             const unsigned char* prev, std::size_t len) {
  const unsigned char* src2 = src + len + 1;
  unsigned char* dst2 = dst + len;
  First first;
  Second second;
  first.step(src, prev, dst);
  for (std::size_t i = 4; i < len; i += 4) {
    first.step(src + i, prev + i, dst + i);
    second.step(src2 + i - 4, dst + i - 4, dst2 + i - 4);
  }
  second.step(src2 + len - 4, dst + len - 4, dst2 + len - 4);
}

using Unfilter = void (*)(const unsigned char*, unsigned char*, const unsigned char*, std::size_t);

// The filters whose pixels form a chain (Sub, Average, Paeth), as 0..2; -1 for the others.
int chained(int type) { return type == 1 ? 0 : type == 3 ? 1 : type == 4 ? 2 : -1; }

constexpr Unfilter kRow4[3] = {row4<Sub4>, row4<Avg4>, row4<Paeth4>};
constexpr Unfilter kPair4[3][3] = {
    {pair4<Sub4, Sub4>, pair4<Sub4, Avg4>, pair4<Sub4, Paeth4>},
    {pair4<Avg4, Sub4>, pair4<Avg4, Avg4>, pair4<Avg4, Paeth4>},
    {pair4<Paeth4, Sub4>, pair4<Paeth4, Avg4>, pair4<Paeth4, Paeth4>}};

// The four-row kernel takes about as long whatever its rows' filters: for four rows, 0.6
// of what the pairs take for Average, 0.45 for Paeth, twice for Sub (BM_Unfilter). So it
// serves rows where Average and Paeth dominate. Filter bytes at raw, raw + len + 1, ...
bool quad_pays(const unsigned char* raw, std::size_t len) {
  int average = 0, paeth = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    average += raw[k * (len + 1)] == 3;
    paeth += raw[k * (len + 1)] == 4;
  }
  return paeth >= 2 || average + paeth >= 3;
}

bool has_sse41() {
  static const bool yes = __builtin_cpu_supports("sse4.1");
  return yes;
}

}  // namespace

void unfilter_rows(const unsigned char* raw, unsigned char* out, const unsigned char* prev,
                   std::size_t len, int bpp, std::uint32_t rows, UnfilterKernels kernels) {
  const bool simd = bpp == 4 && has_sse41();
  const bool quad = bpp == 4 && kernels == UnfilterKernels::kBest && len >= 4 * kQuadMinPixels &&
                    quad_unfilter_supported();
  for (std::uint32_t y = 0; y < rows;) {
    const unsigned char* src = raw + y * (len + 1) + 1;
    unsigned char* dst = out + y * len;
    const int type = src[-1], chain = chained(type);
    if (quad && y + 4 <= rows && quad_pays(src - 1, len)) {
      unfilter_quad(src - 1, dst, prev, len);
      prev = dst + 3 * len;
      y += 4;
      continue;
    }
    if (simd && chain >= 0 && y + 1 < rows && chained(src[len]) >= 0) {
      kPair4[chain][chained(src[len])](src, dst, prev, len);
      prev = dst + len;
      y += 2;
      continue;
    }
    if (type == 0) {
      std::memmove(dst, src, len);
    } else if (type == 2) {
      unup(src, dst, prev, len);
    } else if (simd) {
      kRow4[chain](src, dst, prev, len);
    } else if (bpp == 4) {
      unfilter_scalar<4>(type, src, dst, prev, len);
    } else {
      unfilter_scalar<3>(type, src, dst, prev, len);
    }
    prev = dst;
    ++y;
  }
}

}  // namespace aosuite

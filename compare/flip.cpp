// FLIP from the papers' definitions and NVlabs/flip v1.6's constants. Structure:
//   1. each row of both images -> linear RGB in [0, 1] (LDR: sRGB table; HDR: exposure, tone
//      map, clamp) -> YCxCz, padded with replicated edge pixels;
//   2. horizontal passes of the contrast sensitivity filters (Y, Cx, and the Cz filter's two
//      separable Gaussians) and of the feature filters (Gaussian, 1st and 2nd derivative) on
//      normalised Y, into a ring of 2R + 1 rows per thread;
//   3. vertical passes from the ring, then per pixel: back to linear RGB, clamp, CIELab with
//      Hunt's adjustment, HyAB, the colour-difference remap, edge and point differences,
//      error = colour^(1 - feature).
// Every filter sum is taken in the order the tool takes it (taps from -r to r, starting from
// 0), so the filtered values are the tool's to the bit; the transcendental functions are
// vectorizable approximations (compare/simd_math.hpp) within a few ulp of glibc's.
#include "compare/flip.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "compare/magma.hpp"
#include "compare/parallel_rows.hpp"
#include "compare/simd_math.hpp"
#include "compare/srgb.hpp"

// Hot loops get an AVX2 clone picked at load time; the default build targets baseline x86-64.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define AOSUITE_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define AOSUITE_SIMD_CLONES
#endif

namespace aosuite::flip {
namespace {

constexpr float kPi = 3.14159265358979f;

// FLIP's parameters (paper, section 4): colour quality exponent, cut-off fraction and
// compressed range of the colour error, feature width in degrees. (The feature exponent, 1/2,
// is the square root in the per-pixel tail.)
constexpr float kGqc = 0.7f, kGpc = 0.4f, kGpt = 0.95f, kGw = 0.082f;

// Contrast sensitivity: the achromatic and red-green channels are one Gaussian each, blue-
// yellow the sum of two (a, b as in the paper's equation 2).
constexpr float kA1[3] = {1.0f, 1.0f, 34.1f}, kB1[3] = {0.0047f, 0.0053f, 0.04f};
constexpr float kA2z = 13.5f, kB2z = 0.025f;

// D65 reference white and its inverse.
constexpr float kWhite[3] = {0.950428545f, 1.000000000f, 1.088900371f};
constexpr float kInvWhite[3] = {1.052156925f, 1.000000000f, 0.918357670f};

// Linear sRGB <-> XYZ (D65).
constexpr float kToXyz[9] = {
    10135552.0f / 24577794.0f, 8788810.0f / 24577794.0f, 4435075.0f / 24577794.0f,
    2613072.0f / 12288897.0f,  8788810.0f / 12288897.0f, 887015.0f / 12288897.0f,
    1425312.0f / 73733382.0f,  8788810.0f / 73733382.0f, 70074185.0f / 73733382.0f};
constexpr float kToRgb[9] = {3.241003275f,  -1.537398934f, -0.498615861f,
                             -0.969224334f, 1.875930071f,  0.041554224f,
                             0.055639423f,  -0.204011202f, 1.057148933f};

// Tone mappers as (c^2 k0 + c k1 + k2) / (c^2 k3 + c k4 + k5); Reinhard's row is only used to
// place the exposures. ACES's 0.6 cancels its usual pre-exposure.
constexpr float kToneCoefficients[3][6] = {
    {0.0f, 1.0f, 0.0f, 0.0f, 1.0f, 1.0f},
    {0.6f * 0.6f * 2.51f, 0.6f * 0.03f, 0.0f, 0.6f * 0.6f * 2.43f, 0.6f * 0.59f, 0.14f},
    {0.231683f, 0.013791f, 0.0f, 0.18f, 0.3f, 0.018f},
};

int tone_index(ToneMapper t) {
  return t == ToneMapper::reinhard ? 0 : (t == ToneMapper::aces ? 1 : 2);
}

inline float clamp01(float v) {  // NaN -> 0, as the tool's Min(Max(v, 0), 1)
  const float lo = v > 0.0f ? v : 0.0f;
  return lo > 1.0f ? 1.0f : lo;
}

// x^y for x >= 0. kTool (Options::tool_arithmetic): glibc's powf, as the tool calls it; else a
// vector approximation within a few ulp of it.
template <bool kTool>
[[gnu::always_inline]] inline float power(float x, float y) {
  if constexpr (kTool) {
    return std::pow(x, y);
  } else {
    return simd::pow_nonnegative(x, y);
  }
}

template <bool kTool>
[[gnu::always_inline]] inline float lab_f(float t) {
  constexpr float delta = 6.0f / 29.0f;
  constexpr float delta_square = delta * delta;
  constexpr float delta_cube = delta * delta_square;
  constexpr float factor = 1.0f / (3.0f * delta_square);
  constexpr float term = 4.0f / 29.0f;
  const float v = t > delta_cube ? t : 1.0f;
  float c;
  if constexpr (kTool) {
    c = std::pow(v, 1.0f / 3.0f);  // the tool's powf(x, 1/3)
  } else {
    c = simd::cbrt_positive(v);
  }
  return t > delta_cube ? c : factor * t + term;
}

// Linear RGB -> YCxCz.
inline void to_ycxcz(float r, float g, float b, float& y, float& cx, float& cz) {
  const float x = (kToXyz[0] * r + kToXyz[1] * g + kToXyz[2] * b) * kInvWhite[0];
  const float yy = (kToXyz[3] * r + kToXyz[4] * g + kToXyz[5] * b) * kInvWhite[1];
  const float z = (kToXyz[6] * r + kToXyz[7] * g + kToXyz[8] * b) * kInvWhite[2];
  y = 116.0f * yy - 16.0f;
  cx = 500.0f * (x - yy);
  cz = 200.0f * (yy - z);
}

// Filtered YCxCz -> linear RGB, clamped -> CIELab with Hunt's adjustment (L, a', b').
template <bool kTool>
[[gnu::always_inline]] inline void to_lab_hunt(float y, float cx, float cz, float& l, float& a,
                                               float& b) {
  const float yv = (y + 16.0f) / 116.0f;
  const float x = (yv + cx / 500.0f) * kWhite[0];
  const float yw = yv * kWhite[1];
  const float z = (yv - cz / 200.0f) * kWhite[2];
  const float r = clamp01(kToRgb[0] * x + kToRgb[1] * yw + kToRgb[2] * z);
  const float g = clamp01(kToRgb[3] * x + kToRgb[4] * yw + kToRgb[5] * z);
  const float bl = clamp01(kToRgb[6] * x + kToRgb[7] * yw + kToRgb[8] * z);
  const float fx = lab_f<kTool>((kToXyz[0] * r + kToXyz[1] * g + kToXyz[2] * bl) * kInvWhite[0]);
  const float fy = lab_f<kTool>((kToXyz[3] * r + kToXyz[4] * g + kToXyz[5] * bl) * kInvWhite[1]);
  const float fz = lab_f<kTool>((kToXyz[6] * r + kToXyz[7] * g + kToXyz[8] * bl) * kInvWhite[2]);
  l = 116.0f * fy - 16.0f;
  a = 0.01f * l * (500.0f * (fx - fy));
  b = 0.01f * l * (200.0f * (fy - fz));
}

// The largest HyAB distance (green vs blue) raised to qc, with the scalar library functions
// the tool uses for this one constant.
float max_color_distance() {
  auto lab = [](float r, float g, float b, float out[3]) {
    float t[3];
    for (int i = 0; i < 3; ++i) {
      const float v = kToXyz[3 * i] * r + kToXyz[3 * i + 1] * g + kToXyz[3 * i + 2] * b;
      t[i] = v * kInvWhite[i];
      constexpr float delta = 6.0f / 29.0f;
      t[i] = t[i] > delta * delta * delta ? std::pow(t[i], 1.0f / 3.0f)
                                          : 1.0f / (3.0f * delta * delta) * t[i] + 4.0f / 29.0f;
    }
    out[0] = 116.0f * t[1] - 16.0f;
    out[1] = 0.01f * out[0] * (500.0f * (t[0] - t[1]));
    out[2] = 0.01f * out[0] * (200.0f * (t[1] - t[2]));
  };
  float green[3], blue[3];
  lab(0.0f, 1.0f, 0.0f, green);
  lab(0.0f, 0.0f, 1.0f, blue);
  const float hyab =
      std::fabs(green[0] - blue[0]) + std::sqrt((green[1] - blue[1]) * (green[1] - blue[1]) +
                                                (green[2] - blue[2]) * (green[2] - blue[2]));
  return std::pow(hyab, kGqc);
}

// Separable filter taps (see the FLIP repository's misc/separatedConvolutions.pdf).
struct Filters {
  int spatial_radius = 0, feature_radius = 0, radius = 0;
  std::vector<float> y, cx, cz1, cz2;  // contrast sensitivity, 2 * spatial_radius + 1 taps
  std::vector<float> g, dg, ddg;       // feature: Gaussian, 1st and 2nd derivative
};

Filters make_filters(float ppd) {
  Filters f;
  const float pi_sq = kPi * kPi;
  const float max_b = 0.04f;  // the largest b of the contrast sensitivity Gaussians
  f.spatial_radius = static_cast<int>(std::ceil(3.0f * std::sqrt(max_b / (2.0f * pi_sq)) * ppd));
  const int sw = 2 * f.spatial_radius + 1;
  auto gauss = [&](float x2, float a, float b) {
    return a * std::sqrt(kPi / b) * std::exp(-pi_sq * x2 / b);
  };
  auto gauss_sqrt = [&](float x2, float a, float b) {
    return std::sqrt(a * std::sqrt(kPi / b)) * std::exp(-pi_sq * x2 / b);
  };
  f.y.resize(std::size_t(sw)), f.cx.resize(std::size_t(sw)), f.cz1.resize(std::size_t(sw));
  f.cz2.resize(std::size_t(sw));
  float sum_y = 0, sum_cx = 0, sum_cz1 = 0, sum_cz2 = 0;
  const float dx = 1.0f / ppd;
  for (int i = 0; i < sw; ++i) {
    const float x = static_cast<float>(i - f.spatial_radius) * dx;
    const float x2 = x * x;
    const auto k = std::size_t(i);
    f.y[k] = gauss(x2, kA1[0], kB1[0]);
    f.cx[k] = gauss(x2, kA1[1], kB1[1]);
    f.cz1[k] = gauss_sqrt(x2, kA1[2], kB1[2]);
    f.cz2[k] = gauss_sqrt(x2, kA2z, kB2z);
    sum_y += f.y[k], sum_cx += f.cx[k], sum_cz1 += f.cz1[k], sum_cz2 += f.cz2[k];
  }
  const float norm_y = 1.0f / sum_y, norm_cx = 1.0f / sum_cx;
  const float norm_cz = 1.0f / std::sqrt(sum_cz1 * sum_cz1 + sum_cz2 * sum_cz2);
  for (int i = 0; i < sw; ++i) {
    const auto k = std::size_t(i);
    f.y[k] *= norm_y, f.cx[k] *= norm_cx, f.cz1[k] *= norm_cz, f.cz2[k] *= norm_cz;
  }

  const float sd = 0.5f * kGw * ppd;
  f.feature_radius = static_cast<int>(std::ceil(3.0f * sd));
  const int fw = 2 * f.feature_radius + 1;
  f.g.resize(std::size_t(fw)), f.dg.resize(std::size_t(fw)), f.ddg.resize(std::size_t(fw));
  float g_sum = 0, dg_pos = 0, dg_neg = 0, ddg_pos = 0, ddg_neg = 0;
  for (int i = 0; i < fw; ++i) {
    const float x = static_cast<float>(i - f.feature_radius);
    const auto k = std::size_t(i);
    const float g = std::exp(-(x * x) / (2.0f * sd * sd));
    const float dg = -x * g;
    const float ddg = (x * x / (sd * sd) - 1.0f) * g;
    f.g[k] = g, f.dg[k] = dg, f.ddg[k] = ddg;
    g_sum += g;
    (dg > 0.0f ? dg_pos : dg_neg) += std::fabs(dg);
    (ddg > 0.0f ? ddg_pos : ddg_neg) += std::fabs(ddg);
  }
  // Gaussian weights sum to 1, each derivative's positive and negative weights to +-1 (a sum
  // of 0, possible only for degenerate ppd, leaves the weights 0 instead of NaN).
  auto safe = [](float s) { return s > 0.0f ? s : 1.0f; };
  for (int i = 0; i < fw; ++i) {
    const auto k = std::size_t(i);
    f.g[k] /= safe(g_sum);
    f.dg[k] /= safe(f.dg[k] > 0.0f ? dg_pos : dg_neg);
    f.ddg[k] /= safe(f.ddg[k] > 0.0f ? ddg_pos : ddg_neg);
  }
  f.radius = std::max(f.spatial_radius, f.feature_radius);
  return f;
}

// Where a row's linear RGB comes from.
struct Source {
  enum Kind { srgb8, linear, hdr } kind = srgb8;
  RgbaView ref8, test8;
  RgbFloatView ref, test;
  const float* srgb_table = nullptr;  // 256 entries
  int tone = 1;
};

// Fills YCxCz planes (3 per image) of one image row at [pad, pad + w).
AOSUITE_SIMD_CLONES void load_row(const Source& s, int y, float scale, float* out[6], int pad) {
  const int w = s.kind == Source::srgb8 ? s.ref8.width : s.ref.width;
  for (int img = 0; img < 2; ++img) {
    float* py = out[3 * img] + pad;
    float* pcx = out[3 * img + 1] + pad;
    float* pcz = out[3 * img + 2] + pad;
    if (s.kind == Source::srgb8) {
      const unsigned char* p = (img == 0 ? s.ref8 : s.test8).row(y);
      const float* t = s.srgb_table;
      for (int x = 0; x < w; ++x) {
        to_ycxcz(t[p[4 * x]], t[p[4 * x + 1]], t[p[4 * x + 2]], py[x], pcx[x], pcz[x]);
      }
    } else if (s.kind == Source::linear) {
      const float* p = (img == 0 ? s.ref : s.test).row(y);
      for (int x = 0; x < w; ++x) {
        to_ycxcz(clamp01(p[3 * x]), clamp01(p[3 * x + 1]), clamp01(p[3 * x + 2]), py[x], pcx[x],
                 pcz[x]);
      }
    } else {
      const float* p = (img == 0 ? s.ref : s.test).row(y);
      const float* k = kToneCoefficients[s.tone];
      // Exposed values are bounded so that c^2 stays finite (ACES and Hable saturate long
      // before; the tool's float overflow would give NaN, clamped to 0).
      auto expose = [scale](float v) {
        const float e = v * scale;
        return e > 1e18f ? 1e18f : (e < -1e18f ? -1e18f : e);
      };
      if (s.tone == 0) {
        for (int x = 0; x < w; ++x) {
          const float r = expose(p[3 * x]), g = expose(p[3 * x + 1]), b = expose(p[3 * x + 2]);
          const float lum = 0.2126f * r + 0.7152f * g + 0.0722f * b;
          const float f = 1.0f / (1.0f + lum);
          to_ycxcz(clamp01(r * f), clamp01(g * f), clamp01(b * f), py[x], pcx[x], pcz[x]);
        }
      } else {
        auto tm = [k](float c) {
          return clamp01(((c * c) * k[0] + c * k[1] + k[2]) / (c * c * k[3] + c * k[4] + k[5]));
        };
        for (int x = 0; x < w; ++x) {
          to_ycxcz(tm(expose(p[3 * x])), tm(expose(p[3 * x + 1])), tm(expose(p[3 * x + 2])), py[x],
                   pcx[x], pcz[x]);
        }
      }
    }
    for (int c = 0; c < 3; ++c) {  // replicate the edge pixels into the padding
      float* row = out[3 * img + c];
      std::fill(row, row + pad, row[pad]);
      std::fill(row + pad + w, row + pad + w + pad, row[pad + w - 1]);
    }
  }
}

// out[x] = sum over k of taps[k] * in[x + k], k ascending, for x in [0, w).
AOSUITE_SIMD_CLONES void filter_row(const float* in, const float* taps, int n, float* out, int w) {
  std::fill(out, out + w, 0.0f);
  for (int k = 0; k < n; ++k) {
    const float t = taps[k];
    const float* src = in + k;
    for (int x = 0; x < w; ++x) out[x] += t * src[x];
  }
}

// out[x] = sum over k of taps[k] * rows[k][x], k ascending.
AOSUITE_SIMD_CLONES void filter_column(const float* const* rows, const float* taps, int n,
                                       float* out, int w) {
  std::fill(out, out + w, 0.0f);
  for (int k = 0; k < n; ++k) {
    const float t = taps[k];
    const float* src = rows[k];
    for (int x = 0; x < w; ++x) out[x] += t * src[x];
  }
}

struct PixelConstants {
  float cmax, pccmax;
};

// The per-pixel tail: filtered colours and features of both images -> FLIP error. `max_into`:
// HDR keeps the larger of this exposure's error and what `out` holds.
// Always inlined: each target clone of finish_row below must compile the loop for its own
// instruction set (a shared out-of-line body would be baseline x86-64 only).
template <bool kTool>
[[gnu::always_inline]] inline void finish_row_body(const float* const* v, PixelConstants pc,
                                                   float* out, int w, bool max_into) {
  // v: ref Y, Cx, Cz1, Cz2, test Y, Cx, Cz1, Cz2, ref dx, ddx, dy, ddy, test dx, ddx, dy, ddy
  const float norm = 1.0f / std::sqrt(2.0f);
  const float scale_low = kGpt / pc.pccmax;
  const float inv_high = 1.0f / (pc.cmax - pc.pccmax);
  const float* __restrict ry = v[0];
  const float* __restrict rcx = v[1];
  const float* __restrict rcz1 = v[2];
  const float* __restrict rcz2 = v[3];
  const float* __restrict ty = v[4];
  const float* __restrict tcx = v[5];
  const float* __restrict tcz1 = v[6];
  const float* __restrict tcz2 = v[7];
  const float* __restrict rdx = v[8];
  const float* __restrict rddx = v[9];
  const float* __restrict rdy = v[10];
  const float* __restrict rddy = v[11];
  const float* __restrict tdx = v[12];
  const float* __restrict tddx = v[13];
  const float* __restrict tdy = v[14];
  const float* __restrict tddy = v[15];
  float* __restrict o = out;
#pragma GCC ivdep  // the 16 inputs are distinct rows, none of them `out`
  for (int x = 0; x < w; ++x) {
    float l1, a1, b1, l2, a2, b2;
    to_lab_hunt<kTool>(ry[x], rcx[x], rcz1[x] + rcz2[x], l1, a1, b1);
    to_lab_hunt<kTool>(ty[x], tcx[x], tcz1[x] + tcz2[x], l2, a2, b2);
    const float hyab =
        std::fabs(l1 - l2) + std::sqrt((a1 - a2) * (a1 - a2) + (b1 - b2) * (b1 - b2));
    float cd = power<kTool>(hyab, kGqc);
    cd = cd < pc.pccmax ? cd * scale_low : kGpt + ((cd - pc.pccmax) * inv_high) * (1.0f - kGpt);

    const float edge_ref = std::sqrt(rdx[x] * rdx[x] + rdy[x] * rdy[x]);
    const float edge_test = std::sqrt(tdx[x] * tdx[x] + tdy[x] * tdy[x]);
    const float point_ref = std::sqrt(rddx[x] * rddx[x] + rddy[x] * rddy[x]);
    const float point_test = std::sqrt(tddx[x] * tddx[x] + tddy[x] * tddy[x]);
    const float de = std::fabs(edge_ref - edge_test), dp = std::fabs(point_ref - point_test);
    const float feature = norm * (de > dp ? de : dp);
    const float fd = kTool ? std::pow(feature, 0.5f) : std::sqrt(feature);  // ^qf, qf = 1/2
    float e = power<kTool>(cd, 1.0f - fd);
    e = e > 1.0f ? 1.0f : e;  // guards the approximation; the exact value is <= 1
    o[x] = max_into ? (e > o[x] ? e : o[x]) : e;
  }
}

AOSUITE_SIMD_CLONES void finish_row(const float* const* v, PixelConstants pc, float* out, int w,
                                    bool max_into) {
  finish_row_body<false>(v, pc, out, w, max_into);
}

void finish_row_as_tool(const float* const* v, PixelConstants pc, float* out, int w,
                        bool max_into) {
  finish_row_body<true>(v, pc, out, w, max_into);
}

// Normalised Y for the feature filters: Y / 116 + 16 / 116, in [0, 1].
AOSUITE_SIMD_CLONES void normalise_y(const float* y, float* out, int n) {
  const float a = 1.0f / 116.0f, b = 16.0f / 116.0f;
  for (int i = 0; i < n; ++i) out[i] = y[i] * a + b;
}

// Rows [y0, y1) of the error map, for every exposure in turn (LDR: one, scale unused).
void flip_band(const Source& s, const Filters& f, PixelConstants pc,
               const std::vector<float>& scales, bool as_tool, float* map, int w, int h, int y0,
               int y1) {
  const int pad = f.radius;
  const int padded = w + 2 * pad;
  const int ring = 2 * f.radius + 1;
  const auto W = std::size_t(w), P = std::size_t(padded);
  std::vector<float> in(6 * P), yn(2 * P);
  // Ring planes: ref Y, Cx, Cz1, Cz2, dx, ddx, g, then the same for test.
  constexpr int kPlanes = 14;
  std::vector<float> ring_buf(std::size_t(kPlanes) * std::size_t(ring) * W);
  std::vector<float> acc(16 * W);
  auto plane_row = [&](int plane, int slot) {
    return ring_buf.data() + (std::size_t(plane) * std::size_t(ring) + std::size_t(slot)) * W;
  };
  float* in_rows[6];
  for (int i = 0; i < 6; ++i) in_rows[i] = in.data() + std::size_t(i) * P;
  const int sr = f.spatial_radius, fr = f.feature_radius;
  const int sn = 2 * sr + 1, fn = 2 * fr + 1;

  for (std::size_t e = 0; e < scales.size(); ++e) {
    // Logical row j (y0 - R <= j < y1 + R) lives in slot (j - y0 + R) mod ring.
    auto slot_of = [&](int j) { return (j - y0 + f.radius) % ring; };
    auto horizontal = [&](int j) {
      load_row(s, std::clamp(j, 0, h - 1), scales[e], in_rows, pad);
      const int slot = slot_of(j);
      for (int img = 0; img < 2; ++img) {
        const float* py = in_rows[3 * img];
        const int base = 7 * img;
        filter_row(py + pad - sr, f.y.data(), sn, plane_row(base + 0, slot), w);
        filter_row(in_rows[3 * img + 1] + pad - sr, f.cx.data(), sn, plane_row(base + 1, slot), w);
        filter_row(in_rows[3 * img + 2] + pad - sr, f.cz1.data(), sn, plane_row(base + 2, slot), w);
        filter_row(in_rows[3 * img + 2] + pad - sr, f.cz2.data(), sn, plane_row(base + 3, slot), w);
        float* n = yn.data() + std::size_t(img) * P;
        normalise_y(py, n, padded);
        filter_row(n + pad - fr, f.dg.data(), fn, plane_row(base + 4, slot), w);
        filter_row(n + pad - fr, f.ddg.data(), fn, plane_row(base + 5, slot), w);
        filter_row(n + pad - fr, f.g.data(), fn, plane_row(base + 6, slot), w);
      }
    };
    for (int j = y0 - f.radius; j < y0 + f.radius; ++j) horizontal(j);
    std::vector<const float*> rows_store(std::size_t(std::max(sn, fn)));
    const float** rows = rows_store.data();
    const float* v[16];
    for (int y = y0; y < y1; ++y) {
      horizontal(y + f.radius);
      for (int img = 0; img < 2; ++img) {
        const int base = 7 * img;
        float* a = acc.data() + std::size_t(4 * img) * W;
        auto column = [&](int plane, int r, const std::vector<float>& taps, int slot_plane) {
          const int n = 2 * r + 1;
          for (int k = 0; k < n; ++k) rows[k] = plane_row(plane, slot_of(y - r + k));
          filter_column(rows, taps.data(), n, a + std::size_t(slot_plane) * W, w);
        };
        column(base + 0, sr, f.y, 0);
        column(base + 1, sr, f.cx, 1);
        column(base + 2, sr, f.cz1, 2);
        column(base + 3, sr, f.cz2, 3);
      }
      // Features: the x-derivatives smoothed in y, the y-derivatives of the x-smoothed rows;
      // accumulators 8.. hold ref dx, ddx, dy, ddy, then test's.
      for (int img = 0; img < 2; ++img) {
        const int base = 7 * img;
        float* a = acc.data() + std::size_t(8 + 4 * img) * W;
        auto column = [&](int plane, const std::vector<float>& taps, int slot_plane) {
          for (int k = 0; k < fn; ++k) rows[k] = plane_row(plane, slot_of(y - fr + k));
          filter_column(rows, taps.data(), fn, a + std::size_t(slot_plane) * W, w);
        };
        column(base + 4, f.g, 0);    // dx
        column(base + 5, f.g, 1);    // ddx
        column(base + 6, f.dg, 2);   // dy
        column(base + 6, f.ddg, 3);  // ddy
      }
      for (int i = 0; i < 16; ++i) v[i] = acc.data() + std::size_t(i) * W;
      (as_tool ? finish_row_as_tool : finish_row)(v, pc, map + std::size_t(y) * W, w, e > 0);
    }
  }
}

void check_ppd(const Options& o) {
  if (!(o.ppd > 0.0f) || !std::isfinite(o.ppd) || o.ppd > 1e4f)
    throw std::invalid_argument("flip: pixels per degree must be in (0, 10000]");
}

// Sortable key of a float (ascending order of keys = ascending order of values).
inline std::uint32_t sort_key(float v) {
  const auto u = std::bit_cast<std::uint32_t>(v);
  return (u & 0x80000000u) ? ~u : (u | 0x80000000u);
}

// The k-th smallest of v (0-based), v non-empty: a 16-bit radix pass, then nth_element on one
// bucket.
float kth_smallest(const std::vector<float>& v, std::size_t k) {
  std::vector<std::size_t> count(65536, 0);
  for (float x : v) ++count[sort_key(x) >> 16];
  std::size_t below = 0, bucket = 0;
  for (; bucket < 65536; ++bucket) {
    if (below + count[bucket] > k) break;
    below += count[bucket];
  }
  std::vector<float> in_bucket;
  in_bucket.reserve(count[std::min<std::size_t>(bucket, 65535)]);
  for (float x : v)
    if ((sort_key(x) >> 16) == bucket) in_bucket.push_back(x);
  const std::size_t i = k - below;
  std::nth_element(in_bucket.begin(), in_bucket.begin() + std::ptrdiff_t(i), in_bucket.end(),
                   [](float a, float b) { return sort_key(a) < sort_key(b); });
  return in_bucket[i];
}

}  // namespace

// Pooling (tool/pooling.h): mean, min, max, weighted percentiles of values in [0, 1].
void pool(FlipResult& r, bool tool_float) {
  const std::vector<float>& m = r.error_map;
  const std::size_t n = m.size();
  // Buckets by the top 16 bits of the (non-negative) float: count and sum of each.
  constexpr std::size_t kBuckets = 0x3f81;  // 1.0f is 0x3f800000
  std::vector<std::size_t> count(kBuckets, 0);
  std::vector<double> sum(kBuckets, 0.0);
  float lo = std::numeric_limits<float>::max(), hi = 0.0f;
  double total = 0;
  for (float x : m) {
    const std::size_t b =
        std::min<std::size_t>(std::bit_cast<std::uint32_t>(x) >> 16, kBuckets - 1);
    ++count[b];
    sum[b] += x;
    total += x;
    lo = std::min(lo, x), hi = std::max(hi, x);
  }
  r.mean = n ? total / double(n) : 0.0;
  r.min = n ? lo : 0.0f;
  r.max = hi;
  auto weighted = [&](double p) -> float {
    const double target = p * total;
    if (!(total > 0)) return 0.0f;
    double before = 0;
    std::size_t b = 0;
    for (; b < kBuckets; ++b) {
      if (before + sum[b] > target) break;
      before += sum[b];
    }
    if (b == kBuckets) return hi;
    std::vector<float> in_bucket;
    in_bucket.reserve(count[b]);
    for (float x : m)
      if (std::min<std::size_t>(std::bit_cast<std::uint32_t>(x) >> 16, kBuckets - 1) == b)
        in_bucket.push_back(x);
    std::sort(in_bucket.begin(), in_bucket.end());
    for (float x : in_bucket) {
      before += x;
      if (before > target) return x;
    }
    return in_bucket.empty() ? hi : in_bucket.back();
  };
  if (tool_float) {
    // tool/pooling.h's arithmetic: float sums in row order, and over the sorted values.
    float chain = 0.0f;
    for (float x : m) chain += x;
    r.mean = n ? double(chain / static_cast<float>(n)) : 0.0;
    std::vector<float> sorted(m);
    std::sort(sorted.begin(), sorted.end());
    auto tool_weighted = [&](float p) {
      float running = 0.0f;
      for (float x : sorted) {
        running += x;
        if (running > p * chain) return x;
      }
      return 0.0f;
    };
    r.weighted_median = tool_weighted(0.5f);
    r.first_weighted_quartile = tool_weighted(0.25f);
    r.third_weighted_quartile = tool_weighted(0.75f);
    return;
  }
  r.weighted_median = weighted(0.5);
  r.first_weighted_quartile = weighted(0.25);
  r.third_weighted_quartile = weighted(0.75);
}

namespace {

FlipResult run(const Source& s, int w, int h, const Options& o, const std::vector<float>& scales) {
  check_ppd(o);
  FlipResult r;
  r.width = w, r.height = h;
  if (w <= 0 || h <= 0) return r;
  r.error_map.assign(std::size_t(w) * std::size_t(h), 0.0f);
  const Filters f = make_filters(o.ppd);
  static const PixelConstants pc = [] {
    const float cmax = max_color_distance();
    return PixelConstants{cmax, kGpc * cmax};
  }();
  float* map = r.error_map.data();
  parallel_rows(w, h, [&](int y0, int y1) {
    flip_band(s, f, pc, scales, o.tool_arithmetic, map, w, h, y0, y1);
  });
  // NaN cannot arise from finite inputs; this keeps the promise for any input.
  for (float& x : r.error_map) x = x >= 0.0f ? x : 0.0f;
  pool(r, o.tool_arithmetic);
  return r;
}

const float* srgb_to_linear_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      t[std::size_t(i)] = srgb_to_linear(static_cast<float>(i) / 255.0f);
    }
    return t;
  }();
  return table.data();
}

void check_sizes(int w1, int h1, int w2, int h2) {
  if (w1 != w2 || h1 != h2 || w1 < 0 || h1 < 0)
    throw std::invalid_argument("flip: reference and test differ in size");
}

void check_view(const RgbFloatView& v) {
  if (v.width > 0 && v.height > 0 && (v.data == nullptr || v.stride < 3 * std::size_t(v.width)))
    throw std::invalid_argument("flip: float image view without data or with a short stride");
}

}  // namespace

float pixels_per_degree(float distance_m, float resolution_x, float monitor_width_m) {
  return distance_m * (resolution_x / monitor_width_m) * (kPi / 180.0f);
}

float default_ppd() { return pixels_per_degree(0.7f, 3840.0f, 0.7f); }

FlipResult compare_ldr(RgbaView reference, RgbaView test, const Options& options) {
  check_sizes(reference.width, reference.height, test.width, test.height);
  Source s;
  s.kind = Source::srgb8;
  s.ref8 = reference, s.test8 = test;
  s.srgb_table = srgb_to_linear_table();
  return run(s, reference.width, reference.height, options, {1.0f});
}

FlipResult compare_ldr_linear(RgbFloatView reference, RgbFloatView test, const Options& options) {
  check_sizes(reference.width, reference.height, test.width, test.height);
  check_view(reference), check_view(test);
  Source s;
  s.kind = Source::linear;
  s.ref = reference, s.test = test;
  return run(s, reference.width, reference.height, options, {1.0f});
}

FlipResult compare_hdr(RgbFloatView reference, RgbFloatView test, const Options& options) {
  check_sizes(reference.width, reference.height, test.width, test.height);
  check_view(reference), check_view(test);
  check_ppd(options);
  const int w = reference.width, h = reference.height;
  const int tone = tone_index(options.tone_mapper);

  // Sanitised copies: NaN -> 0, +-inf -> +-FLT_MAX (only when there is something to fix).
  auto sanitise = [&](RgbFloatView v, std::vector<float>& store) {
    bool bad = false;
    for (int y = 0; y < v.height && !bad; ++y)
      for (int i = 0; i < 3 * v.width; ++i) bad |= !std::isfinite(v.row(y)[i]);
    if (!bad) return v;
    store.resize(std::size_t(3) * std::size_t(w) * std::size_t(h));
    for (int y = 0; y < h; ++y)
      for (int i = 0; i < 3 * w; ++i) {
        const float x = v.row(y)[i];
        store[std::size_t(y) * 3 * std::size_t(w) + std::size_t(i)] =
            std::isnan(x) ? 0.0f
                          : std::clamp(x, -std::numeric_limits<float>::max(),
                                       std::numeric_limits<float>::max());
      }
    return RgbFloatView{store.data(), w, h, 3 * std::size_t(w)};
  };
  std::vector<float> ref_store, test_store;
  reference = sanitise(reference, ref_store);
  test = sanitise(test, test_store);

  float start = 0, stop = 0;
  if (!options.start_exposure || !options.stop_exposure) {
    // The tool's automatic range: start where the reference's brightest pixel, stop where its
    // median pixel, maps to 0.85 after tone mapping.
    const float* k = kToneCoefficients[tone];
    const float t = 0.85f;
    const float a = k[0] - t * k[3], b = k[1] - t * k[4], c = k[2] - t * k[5];
    float x_max;
    if (a == 0.0f) {
      x_max = -c / b;
    } else {
      const float d1 = -0.5f * (b / a);
      x_max = d1 + std::sqrt((d1 * d1) - (c / a));
    }
    std::vector<float> lum(std::size_t(w) * std::size_t(h));
    float y_max = -1e30f, y_min_positive = std::numeric_limits<float>::infinity();
    for (int y = 0; y < h; ++y) {
      const float* p = reference.row(y);
      for (int x = 0; x < w; ++x) {
        const float l = 0.2126f * p[3 * x] + 0.7152f * p[3 * x + 1] + 0.0722f * p[3 * x + 2];
        lum[std::size_t(y) * std::size_t(w) + std::size_t(x)] = l;
        y_max = std::max(y_max, l);
        if (l > 0.0f) y_min_positive = std::min(y_min_positive, l);
      }
    }
    float y_median = lum.empty() ? 0.0f : kth_smallest(lum, lum.size() / 2);
    if (!(y_median > 0.0f)) y_median = y_min_positive;  // the tool would divide by 0
    float auto_start = 0, auto_stop = 0;
    if (y_max > 0.0f && std::isfinite(y_max) && std::isfinite(y_median) && x_max > 0.0f) {
      auto_start = static_cast<float>(std::log2(double(x_max / y_max)));
      auto_stop = static_cast<float>(std::log2(double(x_max / y_median)));
      if (!std::isfinite(auto_start) || !std::isfinite(auto_stop)) auto_start = auto_stop = 0;
    }
    start = options.start_exposure.value_or(auto_start);
    stop = options.stop_exposure.value_or(auto_stop);
  } else {
    start = *options.start_exposure, stop = *options.stop_exposure;
  }
  if (!std::isfinite(start) || !std::isfinite(stop) || start > stop)
    throw std::invalid_argument("flip: start exposure must be finite and <= stop exposure");
  int num = 0;
  if (options.num_exposures) {
    num = *options.num_exposures;
    if (num < 1 || num > 1000) throw std::invalid_argument("flip: exposures must be in [1, 1000]");
  } else {
    const float span = std::ceil(stop - start);
    num = span > 1000.0f ? 1000 : static_cast<int>(std::max(2.0f, span));
  }
  const float step = num > 1 ? (stop - start) / static_cast<float>(num - 1) : 0.0f;
  std::vector<float> scales;
  for (int i = 0; i < num; ++i)
    scales.push_back(std::pow(2.0f, start + static_cast<float>(i) * step));

  Source s;
  s.kind = Source::hdr;
  s.ref = reference, s.test = test;
  s.tone = tone;
  FlipResult r = run(s, w, h, options, scales);
  r.start_exposure = start, r.stop_exposure = stop, r.num_exposures = num;
  return r;
}

RgbaImage error_map_image(const FlipResult& result, ErrorMapStyle style) {
  RgbaImage img(result.width, result.height);
  unsigned char* p = img.data();
  for (std::size_t i = 0; i < result.error_map.size(); ++i) {
    const float e = std::clamp(result.error_map[i], 0.0f, 1.0f);
    if (style == ErrorMapStyle::magma) {
      const auto& c = kMagma8[std::size_t(static_cast<int>(e * 255.0f + 0.5f)) % 256];
      p[4 * i] = c[0], p[4 * i + 1] = c[1], p[4 * i + 2] = c[2];
    } else {
      const auto g = static_cast<unsigned char>(255.0f * e + 0.5f);
      p[4 * i] = p[4 * i + 1] = p[4 * i + 2] = g;
    }
    p[4 * i + 3] = 255;
  }
  return img;
}

}  // namespace aosuite::flip

// Branch-free float transcendentals that GCC vectorizes inside loops (glibc's powf and
// cbrtf are scalar calls, and the metric kernels make ~10 of them per pixel). Accuracy:
// cbrt_positive as powf(t, 1.0f / 3.0f) within ~1 ulp, log2 within ~2e-7 absolute, exp2 within
// ~2e-7 relative; pow(x, y) for x in [0, 1], y in [0, 1] (FLIP's exponents) within ~3e-7 relative.
#pragma once

#include <bit>
#include <cstdint>

namespace aosuite::simd {

// t^(1/3) for normal t > 0, as glibc's powf(t, 1.0f / 3.0f) rounds it (FLIP's CIELab uses
// that, and 1.0f / 3.0f exceeds 1/3 by 9.934e-9): an exponent-thirding bit estimate, two
// float Newton steps y <- (2y + t / y^2) / 3, one in double, and the exponent's excess as
// the factor 1 + 9.934e-9 ln t (ln t from the bits, Mitchell's approximation, is plenty).
inline float cbrt_positive(float t) {
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(t);
  float y = std::bit_cast<float>(bits / 3u + 0x2a5137a0u);
  y = (2.0f * y + t / (y * y)) * (1.0f / 3.0f);
  y = (2.0f * y + t / (y * y)) * (1.0f / 3.0f);
  const double yd = double(y), td = double(t);
  const double refined = (2.0 * yd + td / (yd * yd)) * (1.0 / 3.0);
  const double ln_t =  // bits < 2^31 for t > 0
      (double(static_cast<int>(bits)) * (1.0 / 8388608.0) - 127.0) * 0.6931471805599453;
  return static_cast<float>(refined * (1.0 + 9.934107481e-9 * ln_t));
}

// log2(x) for x > 0 (subnormals are scaled first). Cephes logf's polynomial for ln(1 + f),
// f in [sqrt(1/2) - 1, sqrt(2) - 1).
inline float log2_positive(float x) {
  const bool tiny = x < 1.17549435e-38f;
  x = tiny ? x * 8388608.0f : x;  // 2^23
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(x);
  int e = static_cast<int>(bits >> 23) - 127 - (tiny ? 23 : 0);
  float m = std::bit_cast<float>((bits & 0x007fffffu) | 0x3f800000u);  // [1, 2)
  const bool high = m > 1.41421356f;
  m = high ? m * 0.5f : m;
  e += high ? 1 : 0;
  const float f = m - 1.0f;
  const float z = f * f;
  float p = 7.0376836292e-2f;
  p = p * f - 1.1514610310e-1f;
  p = p * f + 1.1676998740e-1f;
  p = p * f - 1.2420140846e-1f;
  p = p * f + 1.4249322787e-1f;
  p = p * f - 1.6668057665e-1f;
  p = p * f + 2.0000714765e-1f;
  p = p * f - 2.4999993993e-1f;
  p = p * f + 3.3333331174e-1f;
  const float ln = f + (p * f * z - 0.5f * z);
  return ln * 1.44269504089f + static_cast<float>(e);
}

// 2^x, clamped to [2^-126, 2^127]. Cephes exp2f's polynomial on [-1/2, 1/2].
inline float exp2_clamped(float x) {
  x = x < -126.0f ? -126.0f : (x > 127.0f ? 127.0f : x);
  const float n = (x + 12582912.0f) - 12582912.0f;  // round to nearest (|x| < 2^22)
  const float f = x - n;
  float p = 1.535336188319500e-4f;
  p = p * f + 1.339887440266574e-3f;
  p = p * f + 9.618437357674640e-3f;
  p = p * f + 5.550332471162809e-2f;
  p = p * f + 2.402264791363012e-1f;
  p = p * f + 6.931472028550421e-1f;
  p = p * f + 1.0f;
  const auto scale =
      std::bit_cast<float>(static_cast<std::uint32_t>(static_cast<int>(n) + 127) << 23);
  return p * scale;
}

// x^y for x >= 0 and y >= 0, with pow's conventions 0^0 = 1 and 0^y = 0 for y > 0.
inline float pow_nonnegative(float x, float y) {
  const float r = exp2_clamped(y * log2_positive(x > 0.0f ? x : 1.0f));
  return y == 0.0f ? 1.0f : (x > 0.0f ? r : 0.0f);
}

}  // namespace aosuite::simd

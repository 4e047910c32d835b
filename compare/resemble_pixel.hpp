// Resemble.js's per-pixel predicates (resemble.js 365-499), each exactly as the library
// computes it. Inline: they run per pixel. Compile users with -ffp-contract=off.
#pragma once

#include <algorithm>
#include <cmath>

namespace aosuite::resemble::pixel {

struct Px {
  int r, g, b, a;
};

inline Px load(const unsigned char* p) { return {p[0], p[1], p[2], p[3]}; }

// isColorSimilar: equal, or strictly closer than the tolerance.
inline bool similar(double a, double b, double tol) { return a == b || std::abs(a - b) < tol; }

// Left to right in doubles; a fused multiply-add would change verdicts.
inline double brightness(const Px& p) { return 0.3 * p.r + 0.59 * p.g + 0.11 * p.b; }

// HSL hue as resemble.js computes it: the "/ 6" sits in an unreachable branch, so the range
// is [0, 6), greys are 0 and ties go to red, then green.
inline double hue(const Px& p) {
  const double r = p.r / 255.0, g = p.g / 255.0, b = p.b / 255.0;
  const double mx = std::max({r, g, b}), mn = std::min({r, g, b});
  if (mx == mn) return 0;
  const double d = mx - mn;
  if (mx == r) return (g - b) / d + (g < b ? 6 : 0);
  if (mx == g) return (b - r) / d + 2;
  return (r - g) / d + 4;
}

inline double colors_distance(const Px& p, double r, double g, double b) {
  return (std::abs(p.r - r) + std::abs(p.g - g) + std::abs(p.b - b)) / 3;
}

// Storing a double into a Uint8ClampedArray: NaN and negatives give 0, ties go to even.
inline unsigned char u8clamp(double x) {
  if (!(x > 0)) return 0;
  if (x >= 255) return 255;
  return static_cast<unsigned char>(std::nearbyint(x));
}

// isAntialiased: the 3x3 neighbourhood by *linear* index into the width x height RGBA image,
// so x - 1 at the left edge reads the previous row's last pixel; indices past the end are
// skipped and negative ones read `undefined`, which counts for nothing.
inline bool antialiased(const unsigned char* img, int width, int height, const Px& src, int x,
                        int y, double max_brightness) {
  const double sb = brightness(src), sh = hue(src);
  const long long len = static_cast<long long>(width) * height;
  int contrast = 0, hue_diff = 0, equal = 0;
  for (int i = -1; i <= 1; ++i) {
    for (int j = -1; j <= 1; ++j) {
      if (i == 0 && j == 0) continue;
      const long long idx = static_cast<long long>(y + j) * width + (x + i);
      if (idx < 0 || idx >= len) continue;
      const Px t = load(img + idx * 4);
      if (std::abs(sb - brightness(t)) > max_brightness) ++contrast;
      if (t.r == src.r && t.g == src.g && t.b == src.b) ++equal;
      if (std::abs(hue(t) - sh) > 0.3) ++hue_diff;
      if (hue_diff > 1 || contrast > 1) return true;
    }
  }
  return equal < 2;
}

}  // namespace aosuite::resemble::pixel

#include "compare/difference_views.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace aosuite::comparison {

namespace {

// The diverging map's ends (Moreland's cool-warm, sRGB) and its white middle.
constexpr double kCool[3] = {59, 76, 192}, kWarm[3] = {180, 4, 38}, kWhite[3] = {255, 255, 255};

// t in [-1, 1]: the cool end at -1, white at 0, the warm end at 1.
void diverging(double t, unsigned char* out) {
  const double* end = t < 0 ? kCool : kWarm;
  const double a = std::min(1.0, std::abs(t));
  for (int c = 0; c < 3; ++c)
    out[c] = static_cast<unsigned char>(std::lround(kWhite[c] + a * (end[c] - kWhite[c])));
  out[3] = 255;
}

}  // namespace

DifferenceViews difference_views(RgbaView expected, RgbaView actual) {
  DifferenceViews v;
  const int w = expected.width, h = expected.height;
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<double> mean_change(n);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char *e = expected.data + 4 * i, *a = actual.data + 4 * i;
    int sum = 0;
    for (int c = 0; c < 3; ++c) {
      v.largest_channel = std::max(v.largest_channel, std::abs(a[c] - e[c]));
      sum += a[c] - e[c];
    }
    mean_change[i] = sum / 3.0;
    v.largest_signed = std::max(v.largest_signed, std::abs(mean_change[i]));
  }
  v.absolute = RgbaImage(w, h);
  v.signed_change = RgbaImage(w, h);
  const double scale = v.largest_channel > 0 ? 255.0 / v.largest_channel : 0;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char *e = expected.data + 4 * i, *a = actual.data + 4 * i;
    unsigned char* out = v.absolute.data() + 4 * i;
    for (int c = 0; c < 3; ++c)
      out[c] = static_cast<unsigned char>(std::lround(std::abs(a[c] - e[c]) * scale));
    out[3] = 255;
    diverging(v.largest_signed > 0 ? mean_change[i] / v.largest_signed : 0,
              v.signed_change.data() + 4 * i);
  }
  return v;
}

}  // namespace aosuite::comparison

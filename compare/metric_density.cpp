// Density: the most differing pixels in any 16 x 16 window (pixelmatch's windowSize idea), so
// one concentrated defect in a big image fails a gate that a whole-image percentage dilutes:
// 100 changed pixels are 0.04 % of 512 x 512 whether they are one 10 x 10 blot or scattered.
// A pixel differs when any of R, G, B moves by more than one 8-bit level (1/255 of the range:
// 1 for 8-bit, 257 for 16-bit, 1/255 for float), so rounding noise is not a defect.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "compare/metric.hpp"

namespace aosuite::metric {
namespace {

constexpr int kWindow = 16;

// 1 where the pixel differs (and is counted), else 0, row-major.
std::vector<std::uint32_t> differing(const Picture& reference, const Picture& test,
                                     const std::vector<std::uint8_t>* counted) {
  const ImageSize size = reference.size();
  const std::size_t pixels = std::size_t(size.width) * std::size_t(size.height);
  std::vector<std::uint32_t> out(pixels, 0);
  for (std::size_t i = 0; i < pixels; ++i) {
    if (counted && !(*counted)[i]) continue;
    bool differs = false;
    if (!reference.is_float) {
      const unsigned char *a = reference.rgba.data() + 4 * i, *b = test.rgba.data() + 4 * i;
      for (int c = 0; c < 3; ++c) differs = differs || std::abs(int(a[c]) - int(b[c])) > 1;
    } else {
      const std::size_t n = std::size_t(reference.floats.channels);
      for (std::size_t c = i * n; c < (i + 1) * n; ++c) {
        const double d = std::abs(double(reference.floats.data[c]) - double(test.floats.data[c]));
        differs = differs || d > 1.0 / 255.0 + 1e-12;  // 16-bit samples are stored as v / 65535
      }
    }
    out[i] = differs;
  }
  return out;
}

constexpr std::string_view kStats[] = {"count", "share"};

Measurement measure_density(const Picture& reference, const Picture& test, const Request& request) {
  const ImageSize size = reference.size();
  const int w = size.width, h = size.height;
  const int ww = std::min(kWindow, w), wh = std::min(kWindow, h);  // small images: one window
  // Summed-area table with a zero row and column: every window's count in O(1).
  const std::vector<std::uint32_t> d = differing(reference, test, request.counted);
  std::vector<std::uint32_t> sat(std::size_t(w + 1) * std::size_t(h + 1), 0);
  const auto at = [&](int x, int y) -> std::uint32_t& {
    return sat[std::size_t(y) * std::size_t(w + 1) + std::size_t(x)];
  };
  for (int y = 0; y < h; ++y) {
    std::uint32_t row = 0;
    for (int x = 0; x < w; ++x) {
      row += d[std::size_t(y) * std::size_t(w) + std::size_t(x)];
      at(x + 1, y + 1) = at(x + 1, y) + row;
    }
  }
  std::uint32_t most = 0;
  for (int y = wh; y <= h; ++y)
    for (int x = ww; x <= w; ++x)
      most = std::max(most, at(x, y) - at(x - ww, y) - at(x, y - wh) + at(x - ww, y - wh));
  Measurement m;
  m.metric = "density";
  const int window_pixels = ww * wh;  // 0 only for an empty image
  m.values = {{"count", double(most)},
              {"share", window_pixels > 0 ? double(most) / window_pixels : 0.0}};
  m.facts = {{"window", double(kWindow)}};
  return m;
}

}  // namespace

extern const Metric kDensity{
    .name = "density",
    .summary =
        "most differing pixels (a channel off by > 1/255) in any 16x16 window, and their share",
    .stats = kStats,
    .primary = "count",
    .measure = measure_density,
};

}  // namespace aosuite::metric

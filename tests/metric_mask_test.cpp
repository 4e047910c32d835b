// Metrics over some pixels only (Request::counted, foreground_only's geometry): every flag set
// is the whole image; a subset pools, averages and sums exactly those pixels' values.
#include <gtest/gtest.h>

#include <random>

#include "compare/flip.hpp"
#include "compare/metric.hpp"
#include "compare/ssim.hpp"

namespace aosuite {
namespace {

Picture noise(int w, int h, unsigned seed) {
  Picture p;
  p.name = "noise" + std::to_string(seed);
  p.rgba = RgbaImage(w, h);
  std::mt19937 rng(seed);
  for (std::size_t i = 0; i < std::size_t(w) * std::size_t(h) * 4; ++i)
    p.rgba.data()[i] = static_cast<unsigned char>(i % 4 == 3 ? 255 : rng() % 256);
  return p;
}

double value(const char* metric_name, const Picture& a, const Picture& b, const char* key,
             const std::vector<std::uint8_t>* counted) {
  return metric::measure(metric::find(metric_name), a, b, {.counted = counted}).value(key);
}

TEST(MetricMask, EveryPixelCountedIsTheWholeImage) {
  const Picture a = noise(37, 23, 1), b = noise(37, 23, 2);
  const std::vector<std::uint8_t> all(37 * 23, 1);
  for (const auto& [m, key] : {std::pair{"flip", "mean"}, std::pair{"flip", "q3"},
                               std::pair{"ssim", "mean"}, std::pair{"rmse", "value"}}) {
    EXPECT_NEAR(value(m, a, b, key, &all), value(m, a, b, key, nullptr), 1e-12) << m << " " << key;
  }
}

TEST(MetricMask, ASubsetCountsExactlyThosePixels) {
  const int w = 41, h = 29;
  const Picture a = noise(w, h, 3), b = noise(w, h, 4);
  std::vector<std::uint8_t> some(std::size_t(w) * h);
  std::mt19937 rng(5);
  for (auto& f : some) f = rng() % 3 == 0;
  // FLIP: the mean of the kept map values.
  flip::FlipResult f = flip::compare_ldr(a.rgba, b.rgba);
  double sum = 0, n = 0;
  for (std::size_t i = 0; i < some.size(); ++i) sum += some[i] ? f.error_map[i] : 0, n += some[i];
  EXPECT_NEAR(value("flip", a, b, "mean", &some), sum / n, 1e-12);
  // SSIM: the mean of each channel's map over the kept pixels inside the 5-pixel crop.
  double ssim = 0;
  for (int c = 0; c < 3; ++c) {
    std::vector<float> pa(some.size()), pb(some.size()), map(some.size());
    for (std::size_t i = 0; i < some.size(); ++i)
      pa[i] = a.rgba.data()[4 * i + c], pb[i] = b.rgba.data()[4 * i + c];
    ssim::Options o;
    ssim::ssim_map({pa.data(), w, h, std::size_t(w), 1}, {pb.data(), w, h, std::size_t(w), 1}, o,
                   map.data());
    double s = 0, k = 0;
    for (int y = 5; y < h - 5; ++y)
      for (int x = 5; x < w - 5; ++x)
        if (some[std::size_t(y) * w + x]) s += map[std::size_t(y) * w + x], ++k;
    ssim += s / k / 3;
  }
  EXPECT_NEAR(value("ssim", a, b, "mean", &some), ssim, 1e-6);  // the map is float
  // RMSE: the kept pixels' R, G, B only.
  double sq = 0, m = 0;
  for (std::size_t i = 0; i < some.size(); ++i) {
    if (!some[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = (a.rgba.data()[4 * i + c] - b.rgba.data()[4 * i + c]) / 255.0;
      sq += d * d, ++m;
    }
  }
  EXPECT_NEAR(value("rmse", a, b, "value", &some), std::sqrt(sq / m), 1e-12);
  // No pixel counted: nothing differs.
  const std::vector<std::uint8_t> none(some.size(), 0);
  EXPECT_EQ(value("ssim", a, b, "mean", &none), 1.0);
  EXPECT_EQ(value("rmse", a, b, "value", &none), 0.0);
  EXPECT_EQ(value("flip", a, b, "mean", &none), 0.0);
  // A mask of another size is refused.
  const std::vector<std::uint8_t> wrong(10, 1);
  EXPECT_THROW(value("rmse", a, b, "value", &wrong), std::invalid_argument);
}

}  // namespace
}  // namespace aosuite

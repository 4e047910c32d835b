// RMSE and PSNR: the mean squared error over R, G, B (or the one grey channel), on values in
// [0, 1] for PNGs (v / 255, v / 65535) and as stored for EXR. PSNR is scikit-image's
// peak_signal_noise_ratio with data_range 1 (+inf for identical images).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "compare/metric.hpp"

namespace aosuite::metric {
namespace {

struct Errors {
  double mse = 0, max_abs = 0;
};

// Over the counted pixels (all without a mask); no pixel counted: no error.
Errors errors(const Picture& reference, const Picture& test,
              const std::vector<std::uint8_t>* counted) {
  Errors e;
  std::size_t n = 0;
  if (!reference.is_float) {
    // Integers: exact sums, one division at the end.
    std::uint64_t squares = 0;
    int worst = 0;
    const RgbaView a = reference.rgba, b = test.rgba;
    for (int y = 0; y < a.height; ++y) {
      const unsigned char *pa = a.row(y), *pb = b.row(y);
      for (int x = 0; x < a.width; ++x) {
        if (counted && !(*counted)[std::size_t(y) * std::size_t(a.width) + std::size_t(x)])
          continue;
        for (int c = 0; c < 3; ++c) {  // alpha is not compared
          const int d = std::abs(int(pa[4 * x + c]) - int(pb[4 * x + c]));
          squares += std::uint64_t(d * d), worst = std::max(worst, d);
        }
        n += 3;
      }
    }
    e.mse = n ? double(squares) / double(n) / (255.0 * 255.0) : 0;
    e.max_abs = worst / 255.0;
    return e;
  }
  const std::vector<float>&a = reference.floats.data, &b = test.floats.data;
  const std::size_t channels = std::size_t(reference.floats.channels);
  if (reference.floats.srgb && test.floats.srgb) {
    // 16-bit samples, held as v / 65535 in float: their integers back (float's error there is
    // under 0.004 of a level), for exact sums. The floats' own difference is off by up to
    // float's step at 1, 0.4 % of one level (a gate near a level misjudged).
    std::uint64_t squares = 0;
    long worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (counted && !(*counted)[i / channels]) continue;
      const long d = std::labs(std::lround(a[i] * 65535.0) - std::lround(b[i] * 65535.0));
      squares += std::uint64_t(d * d), worst = std::max(worst, d);
      ++n;
    }
    e.mse = n ? double(squares) / double(n) / (65535.0 * 65535.0) : 0;
    e.max_abs = double(worst) / 65535.0;
    return e;
  }
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (counted && !(*counted)[i / channels]) continue;
    const double d = double(a[i]) - double(b[i]);
    sum += d * d, e.max_abs = std::max(e.max_abs, std::abs(d));
    ++n;
  }
  e.mse = n ? sum / double(n) : 0;
  return e;
}

constexpr std::string_view kRmseStats[] = {"value", "max_abs"};
constexpr std::string_view kPsnrStats[] = {"db"};

Measurement measure_rmse(const Picture& reference, const Picture& test, const Request& request) {
  const Errors e = errors(reference, test, request.counted);
  Measurement m;
  m.metric = "rmse", m.values = {{"value", std::sqrt(e.mse)}, {"max_abs", e.max_abs}};
  return m;
}

Measurement measure_psnr(const Picture& reference, const Picture& test, const Request& request) {
  const Errors e = errors(reference, test, request.counted);
  Measurement m;
  m.metric = "psnr", m.values = {{"db", psnr_db(e.mse)}}, m.facts = {{"data_range", 1.0}};
  return m;
}

}  // namespace

double psnr_db(double mse, double data_range) {
  return mse > 0 ? 10.0 * std::log10(data_range * data_range / mse) : HUGE_VAL;
}

extern const Metric kRmse{
    .name = "rmse",
    .summary = "root-mean-square error and largest absolute error, values in [0, 1] for PNG",
    .stats = kRmseStats,
    .primary = "value",
    .measure = measure_rmse,
};

extern const Metric kPsnr{
    .name = "psnr",
    .summary = "peak signal-to-noise ratio in dB, data range 1 (null in JSON: identical)",
    .stats = kPsnrStats,
    .primary = "db",
    .measure = measure_psnr,
};

}  // namespace aosuite::metric

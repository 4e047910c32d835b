// SSIM as a metric (compare/ssim.hpp has the kernel): scikit-image's
// structural_similarity(gaussian_weights=True, sigma=1.5, use_sample_covariance=False) with
// data_range 255 on 8-bit R, G, B, and 1 on float images (16-bit PNGs as v / 65535, EXR as
// stored), the mean over channels.
#include "compare/metric.hpp"
#include "compare/ssim.hpp"

namespace aosuite::metric {
namespace {

constexpr std::string_view kStats[] = {"mean"};

Measurement measure_ssim(const Picture& reference, const Picture& test, const Request& request) {
  ssim::Options o;
  if (request.counted) o.counted = request.counted->data();
  ssim::SsimResult r;
  if (!reference.is_float) {
    r = ssim::compare_rgb(reference.rgba, test.rgba, o);
  } else {
    const FloatImage &a = reference.floats, &b = test.floats;
    o.data_range = 1.0;
    const auto n = std::size_t(a.channels);
    r = ssim::compare_channels({a.data.data(), a.width, a.height, std::size_t(a.width) * n, n},
                               {b.data.data(), b.width, b.height, std::size_t(b.width) * n, n},
                               a.channels, o);
  }
  Measurement m;
  m.metric = "ssim";
  m.values = {{"mean", r.mean}};
  m.facts = {{"data_range", o.data_range}};
  return m;
}

}  // namespace

extern const Metric kSsim{
    .name = "ssim",
    .summary = "structural similarity as scikit-image computes it (1 = same)",
    .stats = kStats,
    .primary = "mean",
    .measure = measure_ssim,
};

}  // namespace aosuite::metric

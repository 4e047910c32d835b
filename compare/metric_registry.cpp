// The registered metrics, in the order commands list them. A new metric: its own
// compare/metric_<name>.cpp defining `extern const Metric k<Name>`, and its name here.
#include <array>

#include "compare/metric.hpp"

namespace aosuite::metric {

extern const Metric kFlip, kSsim, kRmse, kPsnr, kDensity;

std::span<const Metric* const> all() {
  static constexpr std::array<const Metric*, 5> kAll{&kFlip, &kSsim, &kRmse, &kPsnr, &kDensity};
  return kAll;
}

const Metric& heatmap_metric() {
  for (const Metric* m : all())
    if (m->heatmap) return *m;
  return *all().front();  // unreachable: FLIP is registered with heatmap = true
}

}  // namespace aosuite::metric

#include "ao/tune_choice.hpp"

#include <algorithm>
#include <cmath>

namespace aosuite::ao {

double error_ratio(double error, double default_error) {
  constexpr double kNegligible = 1e-3;
  return (error + kNegligible) / (default_error + kNegligible);
}

double objective(const std::vector<double>& ratios) {
  if (ratios.empty()) return 1;
  double sum = 0;
  for (double r : ratios) sum += r;
  return 0.5 * (std::ranges::max(ratios) + sum / static_cast<double>(ratios.size()));
}

void summarise(ShrinkTrial& t, const std::vector<double>& ratios, const HeldOutBar& bar) {
  t.pairs = static_cast<int>(ratios.size());
  t.worse = 0, t.worst_ratio = 1, t.mean_ratio = 1, t.log_se = 0;
  bool finite = true;
  double sum = 0;
  for (double r : ratios) {
    finite = finite && std::isfinite(r) && r > 0;
    t.worse += !(r <= 1);
    if (r > t.worst_ratio) t.worst_ratio = r;
    sum += std::log(r);
  }
  const double n = static_cast<double>(ratios.size());
  if (!ratios.empty()) t.mean_ratio = std::exp(sum / n);
  if (ratios.size() > 1) {
    double squares = 0;
    for (double r : ratios) squares += (std::log(r) - sum / n) * (std::log(r) - sum / n);
    t.log_se = std::sqrt(squares / (n - 1) / n);  // the sample standard deviation over sqrt(n)
  }
  // Whole pairs: at most floor(share x pairs) may be worse (a product such as 0.29 x 100 is
  // 28.999... in floating point).
  const int allowed = static_cast<int>(std::floor(bar.worse_share * n + 1e-9));
  t.within_bar = finite && t.worse <= allowed && t.worst_ratio <= bar.worst_ratio;
}

double choose_shrink(const std::vector<ShrinkTrial>& trials) {
  if (trials.empty()) return 1;
  const auto eligible = [](const ShrinkTrial& t) { return t.within_bar && t.within_budget; };
  const ShrinkTrial* best = nullptr;
  for (const ShrinkTrial& t : trials) {
    if (eligible(t) && (!best || t.mean_ratio < best->mean_ratio)) best = &t;
  }
  if (!best || !(best->mean_ratio < 1)) return 0;
  const double enough = std::log(best->mean_ratio) + best->log_se;
  for (const ShrinkTrial& t : trials) {  // in increasing share; share 0's log ratio is 0
    if (eligible(t) && std::log(t.mean_ratio) <= enough) return t.shrink;
  }
  return 0;
}

}  // namespace aosuite::ao

// `aosuite compare`'s tolerance: the one tolerance (compare/tolerance.hpp) from its flags, and
// how its measurements print.
#pragma once

#include <string>
#include <vector>

#include "compare/comparison.hpp"

namespace aosuite::cli {

struct ToleranceFlags {
  std::vector<std::string> metrics;  // --metric: measured, not gated ("flip,ssim" or repeated)
  std::vector<std::string> gates;    // --gate METRIC.KEY=VALUE: beside Resemble's gate
  std::vector<std::string> limits;   // --limit KEY=VALUE, as a suite's [tolerance] keys
  std::string heatmap;               // --heatmap FILE: the heat-map metric is measured
  double threshold = 0;              // --threshold: max_mismatch_percent
  std::string mode;                  // --mode; "default" is Resemble's own, tolerances of less
};

// Throws std::invalid_argument, one line, for an unknown metric, gate or limit.
comparison::Tolerance tolerance_from(const ToleranceFlags& flags);

// One line per measured metric ("flip: mean 0.0312 ...").
std::vector<std::string> metric_lines(const comparison::Comparison& c);

}  // namespace aosuite::cli

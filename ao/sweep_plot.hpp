// A hand-written SVG scatter plot of run time (log x) against error (linear y), one colour per
// series, with the Pareto front (no other point is both faster and more accurate) as a line.
#pragma once

#include <string>
#include <vector>

namespace aosuite::ao {

struct PlotPoint {
  std::string series;   // e.g. the technique
  double x = 0, y = 0;  // x > 0 (log axis)
  std::string label;    // tooltip
};

std::string pareto_svg(const std::vector<PlotPoint>& points, const std::string& title,
                       const std::string& x_label, const std::string& y_label);

// Indices of the Pareto-optimal points (lowest y for their x or less), by increasing x.
std::vector<std::size_t> pareto_front(const std::vector<PlotPoint>& points);

}  // namespace aosuite::ao

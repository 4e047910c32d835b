#include "ao/sweep_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "harness/escape.hpp"

namespace aosuite::ao {
namespace {

constexpr double kW = 760, kH = 480, kLeft = 70, kRight = 150, kTop = 40, kBottom = 55;
constexpr const char* kColours[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a",
                                    "#66a61e", "#e6ab02", "#a6761d", "#666666"};

}  // namespace

std::vector<std::size_t> pareto_front(const std::vector<PlotPoint>& points) {
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return points[a].x != points[b].x ? points[a].x < points[b].x : points[a].y < points[b].y;
  });
  std::vector<std::size_t> front;
  for (std::size_t i : order) {
    if (front.empty() || points[i].y < points[front.back()].y) front.push_back(i);
  }
  return front;
}

std::string pareto_svg(const std::vector<PlotPoint>& points, const std::string& title,
                       const std::string& x_label, const std::string& y_label) {
  double x_min = 1e300, x_max = 0, y_max = 0;
  for (const PlotPoint& p : points) {
    x_min = std::min(x_min, p.x), x_max = std::max(x_max, p.x), y_max = std::max(y_max, p.y);
  }
  if (points.empty()) x_min = 1, x_max = 10, y_max = 1;
  const double lx0 = std::floor(std::log10(x_min)),
               lx1 = std::max(lx0 + 1, std::ceil(std::log10(x_max)));
  y_max = y_max > 0 ? y_max * 1.1 : 1;
  const double pw = kW - kLeft - kRight, ph = kH - kTop - kBottom;
  auto sx = [&](double x) { return kLeft + (std::log10(x) - lx0) / (lx1 - lx0) * pw; };
  auto sy = [&](double y) { return kTop + ph - y / y_max * ph; };

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" "
      "font-family=\"sans-serif\" "
      "font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      "<text x=\"{}\" y=\"22\" font-size=\"15\">{}</text>\n",
      kW, kH, kLeft, harness::escape_markup(title));
  // Axes: decades and 2x, 5x ticks on x; five steps on y.
  for (double d = lx0; d <= lx1; ++d) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double x = m * std::pow(10, d);
      if (std::log10(x) > lx1 + 1e-9) break;
      svg += fmt::format(
          "<line x1=\"{0:.1f}\" y1=\"{1}\" x2=\"{0:.1f}\" y2=\"{2}\" stroke=\"#ddd\"/>"
          "<text x=\"{0:.1f}\" y=\"{3}\" text-anchor=\"middle\">{4:g}</text>\n",
          sx(x), kTop, kTop + ph, kTop + ph + 16, x);
    }
  }
  for (int i = 0; i <= 5; ++i) {
    const double y = y_max * i / 5;
    svg += fmt::format(
        "<line x1=\"{0}\" y1=\"{1:.1f}\" x2=\"{2}\" y2=\"{1:.1f}\" stroke=\"#ddd\"/>"
        "<text x=\"{3}\" y=\"{4:.1f}\" text-anchor=\"end\">{5:.3f}</text>\n",
        kLeft, sy(y), kLeft + pw, kLeft - 6, sy(y) + 4, y);
  }
  svg += fmt::format(
      "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>\n"
      "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n"
      "<text transform=\"translate(18 {}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
      kLeft, kTop, pw, ph, kLeft + pw / 2, kH - 12, harness::escape_markup(x_label), kTop + ph / 2,
      harness::escape_markup(y_label));
  // The front first, so the points sit on top of it.
  std::string line;
  for (std::size_t i : pareto_front(points))
    line += fmt::format("{:.1f},{:.1f} ", sx(points[i].x), sy(points[i].y));
  svg += fmt::format(
      "<polyline points=\"{}\" fill=\"none\" stroke=\"black\" stroke-width=\"1.5\" "
      "stroke-dasharray=\"5 3\"/>\n",
      line);
  std::map<std::string, const char*> colour;
  for (const PlotPoint& p : points) {
    if (!colour.count(p.series)) colour[p.series] = kColours[colour.size() % std::size(kColours)];
    svg += fmt::format(
        "<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"{}\"><title>{}</title></circle>\n",
        sx(p.x), sy(p.y), colour[p.series], harness::escape_markup(p.label));
  }
  double ly = kTop + 10;
  for (const auto& [series, c] : colour) {
    svg += fmt::format(
        "<circle cx=\"{}\" cy=\"{}\" r=\"5\" fill=\"{}\"/><text x=\"{}\" y=\"{}\">{}</text>\n",
        kW - kRight + 20, ly, c, kW - kRight + 32, ly + 4, harness::escape_markup(series));
    ly += 20;
  }
  svg += fmt::format(
      "<line x1=\"{0}\" y1=\"{1}\" x2=\"{2}\" y2=\"{1}\" stroke=\"black\" "
      "stroke-dasharray=\"5 3\"/><text x=\"{3}\" y=\"{4}\">Pareto front</text>\n",
      kW - kRight + 12, ly, kW - kRight + 28, kW - kRight + 32, ly + 4);
  return svg + "</svg>\n";
}

}  // namespace aosuite::ao

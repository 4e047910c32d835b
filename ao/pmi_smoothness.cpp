#include "ao/pmi_smoothness.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace aosuite::ao {

namespace rd = aosuite::renderer;

std::vector<double> used_vertex_values(const rd::PmiObject& o, const std::vector<float>& v) {
  std::vector<bool> in(o.positions.size(), false);
  for (const glm::uvec3& t : o.triangles) in[t.x] = in[t.y] = in[t.z] = true;
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (in[i]) out.push_back(v[i]);
  return out;
}

Smoothness vertex_smoothness(const rd::PmiObject& o, const std::vector<float>& v) {
  Smoothness s;
  const std::vector<double> u = used_vertex_values(o, v);
  s.distinct = std::set<double>(u.begin(), u.end()).size();
  std::size_t edges = 0;
  for (const glm::uvec3& t : o.triangles) {
    for (auto [a, b] : {std::pair{t.x, t.y}, std::pair{t.y, t.z}, std::pair{t.z, t.x}}) {
      const double d = std::abs(v[a] - v[b]);
      s.mean_step += d, s.flat_edges += d == 0, ++edges;
    }
  }
  s.mean_step /= static_cast<double>(edges), s.flat_edges /= static_cast<double>(edges);
  return s;
}

Smoothness image_smoothness(const rd::Images& img) {
  Smoothness s;
  std::set<int> levels;
  double steps = 0;
  for (int y = 0; y + 1 < img.ao.rows; ++y) {
    for (int x = 0; x + 1 < img.ao.cols; ++x) {
      if (img.depth.at<float>(y, x) <= 0) continue;
      const float a = img.ao.at<float>(y, x);
      levels.insert(static_cast<int>(std::lround(a * 255)));
      for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (img.depth.at<float>(y + dy, x + dx) <= 0) continue;
        s.mean_step += std::abs(img.ao.at<float>(y + dy, x + dx) - a), ++steps;
      }
    }
  }
  s.distinct = levels.size();
  s.mean_step /= std::max(1.0, steps);
  return s;
}

}  // namespace aosuite::ao

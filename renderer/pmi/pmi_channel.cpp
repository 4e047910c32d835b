#include "renderer/pmi/pmi_channel.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "renderer/pmi/pmi_item_buffer.hpp"
#include "renderer/pmi/viewpoint_sphere.hpp"

namespace aosuite::renderer {

PmiSettings pmi_settings(const AoParams& params) {
  PmiSettings s;
  s.viewpoints = params.pmi.viewpoints;
  s.width = params.pmi.resolution;
  s.height = std::max(1, params.pmi.resolution * 3 / 4);
  s.importance_best = params.pmi.importance_best;
  return s;
}

void PmiAccumulator::add_view(std::span<const std::uint32_t> counts) {
  const double total = std::accumulate(counts.begin(), counts.end(), 0.0);
  add(counts, total, total, {});
}

void PmiAccumulator::add_view(std::span<const std::uint32_t> counts, double weight,
                              glm::dvec3 colour) {
  add(counts, std::accumulate(counts.begin(), counts.end(), 0.0), weight, colour);
}

void PmiAccumulator::add(std::span<const std::uint32_t> counts, double total, double weight,
                         glm::dvec3 colour) {
  if (counts.size() != s1_.size()) throw std::invalid_argument("PMI: one count per polygon");
  if (!(total > 0) || !(weight > 0)) return;  // a view that sees nothing carries no channel
  total_weight_ += weight;
  const double log_total = std::log2(total);
  for (std::size_t o = 0; o < counts.size(); ++o) {
    if (counts[o] == 0) continue;
    const double q = weight * counts[o] / total;  // w_v p(o|v)
    const double log_p = std::log2(static_cast<double>(counts[o])) - log_total;
    s1_[o] += q;
    s2_[o] += q * log_p;
    if (!c1_.empty()) {
      c1_[o] += (1.0 - colour) * q;
      c2_[o] += (1.0 - colour) * (q * log_p);
    }
  }
}

std::vector<glm::dvec3> PmiAccumulator::colour_pmi() const {
  std::vector<glm::dvec3> out(c1_.size(), glm::dvec3(0));
  for (std::size_t o = 0; o < out.size(); ++o) {
    if (!(s1_[o] > 0)) continue;
    out[o] =
        glm::max(glm::dvec3(0), (c2_[o] - c1_[o] * std::log2(s1_[o] / total_weight_)) / s1_[o]);
  }
  return out;
}

glm::dvec3 viewpoint_colour(glm::vec3 direction) {
  return 0.5 * (1.0 + glm::dvec3(glm::normalize(direction)));
}

std::vector<double> PmiAccumulator::polygon_probability() const {
  std::vector<double> p(s1_.size(), 0.0);
  if (total_weight_ > 0)
    for (std::size_t o = 0; o < p.size(); ++o) p[o] = s1_[o] / total_weight_;
  return p;
}

std::vector<double> PmiAccumulator::pmi() const {
  std::vector<double> out(s1_.size(), 0.0);
  for (std::size_t o = 0; o < out.size(); ++o) {
    if (!(s1_[o] > 0)) continue;
    // A Kullback-Leibler divergence, >= 0; rounding may leave -1e-15.
    out[o] = std::max(0.0, s2_[o] / s1_[o] - std::log2(s1_[o] / total_weight_));
  }
  return out;
}

namespace {

// VMI and PMI(v) of one view given the finished channel.
void view_information(std::span<const std::uint32_t> counts, std::size_t v, PmiChannel& c) {
  const double total = std::accumulate(counts.begin(), counts.end(), 0.0);
  if (!(total > 0)) return;
  double vmi = 0, pmi_v = 0;
  for (std::size_t o = 0; o < counts.size(); ++o) {
    if (counts[o] == 0 || !(c.polygon_probability[o] > 0)) continue;
    const double p_ov = counts[o] / total;
    vmi += p_ov * std::log2(p_ov / c.polygon_probability[o]);
    pmi_v += c.view_probability[v] * p_ov / c.polygon_probability[o] * c.pmi[o];
  }
  c.vmi[v] = vmi, c.view_pmi[v] = pmi_v;
}

// p(V) of importance_best = k: the k lowest-VMI views share kBestViewsShare.
std::vector<double> best_view_weights(const std::vector<double>& vmi, int k) {
  std::vector<std::size_t> order(vmi.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return vmi[a] < vmi[b]; });
  const auto n = static_cast<double>(vmi.size());
  const double rest =
      vmi.size() > static_cast<std::size_t>(k) ? (1 - kBestViewsShare) / (n - k) : 0;
  std::vector<double> w(vmi.size(), rest);
  for (int i = 0; i < k; ++i) w[order[static_cast<std::size_t>(i)]] = kBestViewsShare / k;
  return w;
}

}  // namespace

PmiChannel compute_pmi_channel(const PmiObject& object, const PmiSettings& s) {
  if (s.width < 16 || s.height < 12 || s.width > 8192 || s.height > 8192)
    throw std::invalid_argument("pmi_resolution must be 16..8192");
  const Icosphere sphere = make_icosphere(s.viewpoints);
  if (s.importance_best < 0 || s.importance_best > s.viewpoints)
    throw std::invalid_argument("importance_best must be 0..viewpoints");
  PmiChannel c;
  for (const glm::vec3& d : sphere.vertices)
    c.viewpoints.push_back(object.centre + d * (kSphereFactor * object.radius));
  ItemBuffer items(object, s.width, s.height);
  const std::size_t n_v = c.viewpoints.size();

  std::vector<double> weights(n_v, 0.0);  // p(v) up to a constant
  auto accumulate_channel = [&](bool by_area) {
    PmiAccumulator acc(object.triangles.size(), s.colour);
    for (std::size_t v = 0; v < n_v; ++v) {
      const auto& counts = items.count(c.viewpoints[v]);
      const double total = std::accumulate(counts.begin(), counts.end(), 0.0);
      if (by_area || !(total > 0)) weights[v] = total;  // a view that sees nothing has p(v) = 0
      acc.add_view(counts, weights[v], viewpoint_colour(c.viewpoints[v] - object.centre));
    }
    const double sum = std::accumulate(weights.begin(), weights.end(), 0.0);
    c.view_probability.assign(n_v, 0.0);
    for (std::size_t v = 0; v < n_v; ++v) c.view_probability[v] = sum > 0 ? weights[v] / sum : 0.0;
    c.polygon_probability = acc.polygon_probability();
    c.pmi = acc.pmi();
    c.colour_pmi = acc.colour_pmi();
  };
  auto per_view = [&] {
    c.vmi.assign(n_v, 0.0), c.view_pmi.assign(n_v, 0.0);
    for (std::size_t v = 0; v < n_v; ++v) view_information(items.count(c.viewpoints[v]), v, c);
  };

  accumulate_channel(true);
  if (s.importance_best > 0) {
    per_view();  // the best views of the area channel
    weights = best_view_weights(c.vmi, s.importance_best);
    accumulate_channel(false);
  }
  if (s.per_view) per_view();
  return c;
}

PmiMaps compute_pmi_maps(const Scene& scene, const PmiSettings& settings) {
  PmiMaps m;
  m.object = pmi_object(scene);
  m.channel = compute_pmi_channel(m.object, settings);
  m.polygon_visibility = polygon_visibility(m.channel);
  m.vertex_visibility = vertex_visibility(m.object, m.polygon_visibility);
  return m;
}

namespace {

// 1 - (x - min) / (max - min) over the polygons some view saw; 0 for the others.
template <typename Value>
std::vector<float> normalised_complement(const std::vector<double>& p_o, Value value) {
  double lo = INFINITY, hi = 0;
  for (std::size_t o = 0; o < p_o.size(); ++o) {
    if (p_o[o] > 0) lo = std::min(lo, value(o)), hi = std::max(hi, value(o));
  }
  std::vector<float> vis(p_o.size(), 0.0f);
  for (std::size_t o = 0; o < vis.size(); ++o) {
    if (!(p_o[o] > 0)) continue;  // never seen: fully occluded
    vis[o] = hi > lo ? static_cast<float>(1 - (value(o) - lo) / (hi - lo)) : 1.0f;
  }
  return vis;
}

}  // namespace

std::vector<float> polygon_visibility(const PmiChannel& c) {
  return normalised_complement(c.polygon_probability, [&](std::size_t o) { return c.pmi[o]; });
}

std::vector<glm::vec3> polygon_colour_visibility(const PmiChannel& c) {
  std::vector<glm::vec3> rgb(c.colour_pmi.size());
  for (int a = 0; a < 3; ++a) {
    const std::vector<float> channel = normalised_complement(
        c.polygon_probability, [&](std::size_t o) { return c.colour_pmi[o][a]; });
    for (std::size_t o = 0; o < rgb.size(); ++o) rgb[o][a] = channel[o];
  }
  return rgb;
}

std::vector<float> vertex_visibility(const PmiObject& object, std::span<const float> polygon) {
  std::vector<double> sum(object.positions.size(), 0.0), area(object.positions.size(), 0.0),
      plain(object.positions.size(), 0.0);
  std::vector<int> count(object.positions.size(), 0);
  for (std::size_t o = 0; o < object.triangles.size(); ++o) {
    const glm::uvec3 t = object.triangles[o];
    const glm::vec3 a = object.positions[t.x], b = object.positions[t.y], c = object.positions[t.z];
    const double w = 0.5 * glm::length(glm::cross(b - a, c - a));
    for (unsigned i : {t.x, t.y, t.z})
      sum[i] += w * polygon[o], area[i] += w, plain[i] += polygon[o], ++count[i];
  }
  std::vector<float> vis(object.positions.size(), 1.0f);  // no polygon: nothing occludes it
  for (std::size_t i = 0; i < vis.size(); ++i) {
    // Only zero-area polygons around it: their plain average.
    if (area[i] > 0 && std::isfinite(sum[i] / area[i]))
      vis[i] = static_cast<float>(sum[i] / area[i]);
    else if (count[i] > 0)
      vis[i] = static_cast<float>(plain[i] / count[i]);
  }
  return vis;
}

}  // namespace aosuite::renderer

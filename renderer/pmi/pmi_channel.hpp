// Viewpoint-based ambient occlusion (González, Sbert & Feixas, IEEE CG&A 2008): the
// information channel V -> O between viewpoints on a sphere around the object and its
// polygons, and polygonal mutual information PMI(o) as an occlusion measure (section 7 of the
// AO-techniques specification that docs/results.md names).
//
// Viewpoints: the vertices of a subdivided icosahedron on a sphere of kSphereFactor times the
// object's bounding-sphere radius, each a perspective camera looking at the centre whose
// vertical field of view just holds the bounding sphere (so the whole object is in view).
// "The object" is every mesh not marked `ground`: a ground plane would fill the viewpoint
// sphere and hide the object's own occlusion, so it takes no part and gets visibility 1.
// Every function here needs a current GL context (a live Renderer) except PmiAccumulator.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "renderer/pmi/pmi_object.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/technique.hpp"

namespace aosuite::renderer {

// The viewpoint sphere's radius over the object's bounding-sphere radius (Quoniam's typical 3).
inline constexpr float kSphereFactor = 3;
// With importance_best = k, the k best views share this much of p(V), the rest share the rest.
// Best = lowest VMI of the area channel (Feixas et al. 2009: the most balanced projection).
inline constexpr double kBestViewsShare = 0.99;

struct PmiSettings {
  int viewpoints = 162;            // 12, 42, 162, 642 or 2562
  int width = 1280, height = 960;  // item buffer
  int importance_best = 0;         // 0: p(v) = projected area; k: the k best views dominate
  bool per_view = false;           // also VMI and PMI(v) (one more round of renders)
  bool colour = false;             // also colour PMI (eq. 12) with viewpoint_colour()
};
PmiSettings pmi_settings(const AoParams& params);  // height = 3/4 of pmi_resolution

// Streaming evaluation with memory per polygon: with q_v(o) = w_v p(o|v) for view weights w_v
// (p(v) = w_v / W), S1(o) = sum_v q_v(o) and S2(o) = sum_v q_v(o) log2 p(o|v) give
// p(o) = S1/W and PMI(o) = sum_v p(v|o) log2(p(o|v)/p(o)) = S2/S1 - log2(S1/W). Terms with
// a_o(v) = 0 contribute nothing (x log x -> 0).
//
// Colour PMI (the paper's eq. 12), I^a(o) = sum_v I(o,v) (1 - c_a(v)) with the matrix element
// I(o,v) = p(v|o) log2(p(v|o)/p(v)), streams the same way: with C1 = sum_v (1 - c(v)) q_v(o)
// and C2 = sum_v (1 - c(v)) q_v(o) log2 p(o|v), I^a(o) = (C2 - C1 log2(S1/W)) / S1.
class PmiAccumulator {
 public:
  explicit PmiAccumulator(std::size_t polygons, bool colour = false)
      : s1_(polygons, 0.0), s2_(polygons, 0.0), c1_(colour ? polygons : 0), c2_(c1_) {}
  // One view's pixel count per polygon, a_o(v), with p(v) proportional to its area a_t(v)
  // (the paper's channel) or to `weight`, and the view's colour c(v) when colour is on.
  void add_view(std::span<const std::uint32_t> counts);
  void add_view(std::span<const std::uint32_t> counts, double weight, glm::dvec3 colour = {});
  std::vector<double> polygon_probability() const;  // p(o); 0 if never seen
  std::vector<double> pmi() const;                  // PMI(o) >= 0 in bits; 0 if never seen
  std::vector<glm::dvec3> colour_pmi() const;       // I^a(o) per channel; empty if colour off

 private:
  void add(std::span<const std::uint32_t> counts, double total, double weight, glm::dvec3 colour);
  std::vector<double> s1_, s2_;
  std::vector<glm::dvec3> c1_, c2_;
  double total_weight_ = 0;
};

// The colour of a viewpoint for colour PMI: an RGB-cube texture warped to the viewpoint
// sphere, c(v) = (1 + direction) / 2 (the paper warps any colour texture to the sphere).
glm::dvec3 viewpoint_colour(glm::vec3 direction);

struct PmiChannel {
  std::vector<glm::vec3> viewpoints;        // world positions of the cameras
  std::vector<double> view_probability;     // p(v)
  std::vector<double> polygon_probability;  // p(o); 0 for polygons no view saw
  std::vector<double> pmi;                  // PMI(o) in bits
  std::vector<double> vmi, view_pmi;        // I(v;O) and PMI(v) = sum_o p(v|o) PMI(o), if per_view
  std::vector<glm::dvec3> colour_pmi;       // I^a(o) per colour channel, if colour
};
PmiChannel compute_pmi_channel(const PmiObject& object, const PmiSettings& settings);

// Everything the renderer and the viewpoints command need of one scene.
struct PmiMaps {
  PmiObject object;
  PmiChannel channel;
  std::vector<float> polygon_visibility, vertex_visibility;  // per object polygon / vertex
};
PmiMaps compute_pmi_maps(const Scene& scene, const PmiSettings& settings);

// The occlusion map per polygon: PMI normalised to [0, 1] over the seen polygons and
// complemented, 1 - (PMI - min) / (max - min), so 1 = open; 0 for polygons never seen. The
// paper "normalized the PMI of all polygons between 0 and 1"; min-max keeps open surfaces white
// as its figures show (1 - PMI/max would leave them grey: a convex polygon still has PMI ~ 1
// bit). A convex object's PMI is near-uniform, so its map only stretches that small range.
std::vector<float> polygon_visibility(const PmiChannel& channel);
// The colour AO map per polygon: each channel of colour PMI normalised and complemented as
// polygon_visibility does (the paper combines the channels after normalising each).
std::vector<glm::vec3> polygon_colour_visibility(const PmiChannel& channel);
// Per object vertex: the area-weighted average of its polygons' visibility.
std::vector<float> vertex_visibility(const PmiObject& object, std::span<const float> polygon);

}  // namespace aosuite::renderer

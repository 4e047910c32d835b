// Viewpoint-based AO (PMI): the channel's invariants on small scenes at low resolution (few
// viewpoints, 160x120 item buffers), and the technique through the Renderer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "renderer/params.hpp"
#include "renderer/pmi/pmi_cache.hpp"
#include "renderer/pmi/pmi_channel.hpp"
#include "renderer/pmi/viewpoint_sphere.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene.hpp"

namespace aosuite::renderer {
namespace {

Renderer& shared_renderer() {  // the GL context every PMI computation needs
  static Renderer r;
  return r;
}

PmiChannel channel(const Scene& scene, int viewpoints, int width = 160) {
  shared_renderer();
  PmiSettings s;
  s.viewpoints = viewpoints, s.width = width, s.height = width * 3 / 4, s.per_view = true;
  return compute_pmi_channel(pmi_object(scene), s);
}

// A geodesic sphere: triangles of near-equal area (a UV sphere's pole slivers are subpixel).
Scene sphere_scene() {
  const Icosphere ico = make_icosphere(642);
  Mesh m;
  m.positions = ico.vertices, m.normals = ico.vertices, m.triangles = ico.faces;
  return {"sphere", {m}, {}};
}

// A block with a groove along z: two walls 1 high on a floor 0.2 high, 0.4 apart.
Scene notch_scene() {
  Scene s{"notch", {}, {{"front", {0, 3, 4}, {0, 0.5f, 0}}}};
  s.meshes.push_back(make_box({-1, 0, -1}, {-0.2f, 1, 1}, glm::vec3(0.8f)));
  s.meshes.push_back(make_box({0.2f, 0, -1}, {1, 1, 1}, glm::vec3(0.8f)));
  s.meshes.push_back(make_box({-0.2f, 0, -1}, {0.2f, 0.2f, 1}, glm::vec3(0.8f)));
  Mesh ground = make_quad({-5, 0, -5}, {0, 0, 10}, {10, 0, 0}, glm::vec3(0.5f));
  ground.ground = true;
  s.meshes.push_back(ground);
  return s;
}

// Mean of `values` over the object polygons whose centroid satisfies `where`.
template <typename T, typename F>
double mean_where(const PmiObject& o, const std::vector<T>& values, F where) {
  double sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < o.triangles.size(); ++i) {
    const glm::uvec3 t = o.triangles[i];
    const glm::vec3 c = (o.positions[t.x] + o.positions[t.y] + o.positions[t.z]) / 3.0f;
    if (where(c)) sum += values[i], ++n;
  }
  EXPECT_GT(n, 0);
  return n ? sum / n : 0;
}

double mean_abs_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d += std::abs(a[i] - b[i]);
  return d / static_cast<double>(a.size());
}

TEST(Pmi, IcosphereHasTheSubdivisionCounts) {
  for (int n : {12, 42, 162, 642}) {
    const Icosphere s = make_icosphere(n);
    EXPECT_EQ(s.vertices.size(), static_cast<std::size_t>(n));
    EXPECT_EQ(s.faces.size(), static_cast<std::size_t>(2 * n - 4));  // Euler: F = 2V - 4
    for (const glm::vec3& v : s.vertices) EXPECT_NEAR(glm::length(v), 1.0f, 1e-5f);
  }
  EXPECT_THROW(make_icosphere(100), std::invalid_argument);
}

TEST(Pmi, AccumulatorMatchesTheDefinition) {
  // Two views, three polygons: PMI(o) = sum_v p(v|o) log2(p(v|o)/p(v)) computed directly.
  const std::vector<std::vector<std::uint32_t>> a = {{30, 10, 0}, {5, 5, 40}};
  PmiAccumulator acc(3);
  for (const auto& counts : a) acc.add_view(counts);
  const double at[2] = {40, 50}, total = 90;
  const std::vector<double> pmi = acc.pmi(), po = acc.polygon_probability();
  for (std::size_t o = 0; o < 3; ++o) {
    const double ao = a[0][o] + a[1][o];
    double expected = 0;
    for (std::size_t v = 0; v < 2; ++v) {
      if (a[v][o] == 0) continue;
      const double p_vo = a[v][o] / ao, p_v = at[v] / total;
      expected += p_vo * std::log2(p_vo / p_v);
    }
    EXPECT_NEAR(pmi[o], expected, 1e-12) << o;
    EXPECT_NEAR(po[o], ao / total, 1e-12) << o;
  }
}

TEST(Pmi, ColourPmiWithOneColourIsScaledPmi) {
  // The paper: "when all sources have the same intensity, the extension reverts to PMI".
  const std::vector<std::vector<std::uint32_t>> a = {{30, 10, 0}, {5, 5, 40}, {0, 7, 9}};
  PmiAccumulator acc(3, true);
  for (const auto& counts : a) {
    const double total = std::accumulate(counts.begin(), counts.end(), 0.0);
    acc.add_view(counts, total, glm::dvec3(0.25, 0.5, 1));
  }
  const std::vector<double> pmi = acc.pmi();
  const std::vector<glm::dvec3> colour = acc.colour_pmi();
  for (std::size_t o = 0; o < 3; ++o) {
    EXPECT_NEAR(colour[o].r, 0.75 * pmi[o], 1e-12);
    EXPECT_NEAR(colour[o].g, 0.5 * pmi[o], 1e-12);
    EXPECT_NEAR(colour[o].b, 0, 1e-12);
  }
}

TEST(Pmi, ColourMapFollowsTheViewpointColours) {
  shared_renderer();
  PmiSettings s;
  s.viewpoints = 42, s.width = 160, s.height = 120, s.colour = true;
  const PmiObject o = pmi_object(notch_scene());
  const std::vector<glm::vec3> rgb = polygon_colour_visibility(compute_pmi_channel(o, s));
  ASSERT_EQ(rgb.size(), o.triangles.size());
  for (const glm::vec3& c : rgb) EXPECT_TRUE(glm::all(glm::greaterThanEqual(c, glm::vec3(0))));
  // Views from +x are reddish (c = (1 + d) / 2): the +x outer wall is lit more in red than in
  // the other channels, relative to the -x wall.
  auto wall = [](float x) { return [x](glm::vec3 p) { return std::abs(p.x - x) < 1e-4f; }; };
  std::vector<float> red_minus_blue(rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) red_minus_blue[i] = rgb[i].r - rgb[i].b;
  EXPECT_GT(mean_where(o, red_minus_blue, wall(1)), mean_where(o, red_minus_blue, wall(-1)));
}

TEST(Pmi, ProbabilitiesSumToOneAndInformationIsNonNegative) {
  const PmiChannel c = channel(notch_scene(), 42);
  EXPECT_NEAR(std::accumulate(c.view_probability.begin(), c.view_probability.end(), 0.0), 1, 1e-9);
  EXPECT_NEAR(std::accumulate(c.polygon_probability.begin(), c.polygon_probability.end(), 0.0), 1,
              1e-9);
  for (double p : c.pmi) EXPECT_TRUE(p >= 0 && std::isfinite(p));
  for (double v : c.vmi) EXPECT_TRUE(v >= 0 && std::isfinite(v));
  for (double v : c.view_pmi) EXPECT_TRUE(v >= 0 && std::isfinite(v));
}

TEST(Pmi, ImportanceGoesToTheBestViews) {
  shared_renderer();
  PmiSettings s;
  s.viewpoints = 42, s.width = 160, s.height = 120, s.importance_best = 2;
  const PmiChannel area = channel(notch_scene(), 42);
  const PmiChannel best = compute_pmi_channel(pmi_object(notch_scene()), s);
  // The two lowest-VMI views of the area channel share 99 %.
  std::vector<double> p = best.view_probability;
  std::sort(p.rbegin(), p.rend());
  EXPECT_NEAR(p[0] + p[1], kBestViewsShare, 1e-9);
  const auto lowest = std::min_element(area.vmi.begin(), area.vmi.end()) - area.vmi.begin();
  EXPECT_NEAR(best.view_probability[static_cast<std::size_t>(lowest)], kBestViewsShare / 2, 1e-9);
  EXPECT_NEAR(std::accumulate(p.begin(), p.end(), 0.0), 1, 1e-9);
  EXPECT_NE(best.pmi, area.pmi);  // p(V) changes PMI (the paper's Figure 7)
  for (double x : best.pmi) EXPECT_TRUE(x >= 0 && std::isfinite(x));
}

TEST(Pmi, ConvexSphereIsNearUniform) {
  const PmiChannel c = channel(sphere_scene(), 42, 320);
  const auto [lo, hi] = std::minmax_element(c.pmi.begin(), c.pmi.end());
  // Every polygon of a sphere is seen by about a hemisphere of views: PMI near 1 bit,
  // within 20 % of each other (a groove's floor has several times its walls' PMI).
  EXPECT_GT(*lo, 0.5);
  EXPECT_LT(*hi, 1.2 * *lo);
}

TEST(Pmi, NotchFloorIsDarkerThanTheTop) {
  const PmiObject o = pmi_object(notch_scene());
  const PmiChannel c = channel(notch_scene(), 42);
  const std::vector<float> vis = polygon_visibility(c);
  auto floor = [](glm::vec3 p) { return std::abs(p.y - 0.2f) < 1e-4f && std::abs(p.x) < 0.2f; };
  auto top = [](glm::vec3 p) { return std::abs(p.y - 1) < 1e-4f; };
  EXPECT_GT(mean_where(o, c.pmi, floor), 1.5 * mean_where(o, c.pmi, top));
  EXPECT_LT(mean_where(o, vis, floor), mean_where(o, vis, top) - 0.3);
  for (float v : vis) EXPECT_TRUE(v >= 0 && v <= 1);
}

TEST(Pmi, IndependentOfPolygonOrder) {
  Scene shuffled = notch_scene();
  for (Mesh& m : shuffled.meshes)
    std::shuffle(m.triangles.begin(), m.triangles.end(), std::mt19937(7));
  const PmiObject a = pmi_object(notch_scene()), b = pmi_object(shuffled);
  const PmiChannel ca = channel(notch_scene(), 12), cb = channel(shuffled, 12);
  // Match polygons by their vertex indices (the shuffle keeps vertices in place).
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    const auto j = static_cast<std::size_t>(
        std::find(b.triangles.begin(), b.triangles.end(), a.triangles[i]) - b.triangles.begin());
    ASSERT_LT(j, b.triangles.size());
    EXPECT_NEAR(ca.pmi[i], cb.pmi[j], 1e-9) << i;
  }
}

TEST(Pmi, MoreViewpointsConverge) {
  const Scene s = notch_scene();
  const std::vector<float> v12 = polygon_visibility(channel(s, 12)),
                           v162 = polygon_visibility(channel(s, 162)),
                           v642 = polygon_visibility(channel(s, 642));
  EXPECT_LT(mean_abs_difference(v162, v642), mean_abs_difference(v12, v642));
}

TEST(Pmi, VertexValuesAreAreaWeighted) {
  // One vertex shared by a triangle of area 2 (visibility 1) and one of area 0.5 (visibility 0).
  PmiObject o;
  o.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {-1, 0, 0}, {0, -1, 0}};
  o.triangles = {{0, 1, 2}, {0, 3, 4}};
  const std::vector<float> v = vertex_visibility(o, std::vector<float>{1, 0});
  EXPECT_NEAR(v[0], 2.0 / 2.5, 1e-6);
  EXPECT_EQ(v[1], 1.0f);
  EXPECT_EQ(v[3], 0.0f);
}

TEST(Pmi, SceneWithOnlyGroundIsAnError) {
  EXPECT_THROW(pmi_object(builtin_scene("plane")), std::invalid_argument);
  RenderSettings s;
  s.width = 64, s.height = 48, s.technique = Technique::kPmi,
  s.params = default_params(s.technique);
  const Scene plane = builtin_scene("plane");
  EXPECT_THROW(shared_renderer().render(plane, plane.views[0], s), std::invalid_argument);
}

TEST(Pmi, RendersThroughThePipelineOnceForAllViews) {
  const Scene s = notch_scene();
  RenderSettings rs;
  rs.width = 128, rs.height = 96, rs.technique = Technique::kPmi;
  rs.params = default_params(Technique::kPmi);
  rs.params.pmi.viewpoints = 42, rs.params.pmi.resolution = 160, rs.params.blur = Blur::kNone;
  View top = s.views[0];
  top.eye = {0.1f, 6, 0.1f}, top.target = {0, 0, 0};
  const Images a = shared_renderer().render(s, s.views[0], rs);
  const auto maps = shared_renderer().pmi_maps(s, pmi_settings(rs.params));
  const Images b = shared_renderer().render(s, top, rs);
  EXPECT_EQ(shared_renderer().pmi_maps(s, pmi_settings(rs.params)), maps);  // cached, not redone
  for (const Images* img : {&a, &b}) {
    ASSERT_FALSE(img->ao.empty());
    EXPECT_TRUE(cv::checkRange(img->ao, true, nullptr, 0.0, 1.0 + 1e-6));
    ASSERT_FALSE(img->with_ao.empty());
  }
  // From above: the groove's floor (image centre column) is darker than a wall top.
  const float floor = b.ao.at<float>(48, 64), wall = b.ao.at<float>(48, 40);
  EXPECT_LT(floor, wall - 0.2f);
  EXPECT_EQ(b.ao.at<float>(5, 5), 1.0f);  // ground: 1 (not part of the object)
}

// Unblurred PMI at 64x48, and maps giving every vertex of `s`'s object the visibility `v`.
RenderSettings unblurred_pmi() {
  RenderSettings rs;
  rs.width = 64, rs.height = 48, rs.technique = Technique::kPmi;
  rs.params = default_params(Technique::kPmi);
  rs.params.blur = Blur::kNone;
  return rs;
}
PmiMaps uniform_maps(const Scene& s, float v) {
  PmiMaps maps;
  maps.object = pmi_object(s);
  maps.vertex_visibility.assign(maps.object.positions.size(), v);
  return maps;
}

// The pixels of `ao` at `value` (interpolation may round by an ulp or so); -1 when a pixel is
// neither that nor 1 (ground and sky).
int pixels_at(const cv::Mat& ao, float value) {
  int n = 0;
  for (int y = 0; y < ao.rows; ++y) {
    for (int x = 0; x < ao.cols; ++x) {
      const float a = ao.at<float>(y, x);
      if (std::abs(a - value) < 1e-5f) {
        ++n;
      } else if (std::abs(a - 1.0f) >= 1e-5f) {
        return -1;
      }
    }
  }
  return n;
}

// The Renderer's PMI cache holds maps by memory, not by scene count: eight scenes visited in
// turn, twice (as a tune's every trial visits them), are computed once each; under a budget of
// one scene's maps each is computed again, and the newest is always kept.
TEST(Pmi, CacheHoldsWhatItsMemoryBudgetAllows) {
  shared_renderer();
  PmiSettings ps;
  ps.viewpoints = 12, ps.width = 32, ps.height = 24;
  std::vector<Scene> scenes;
  for (int i = 0; i < 8; ++i) {  // eight contents: one box a little taller in each
    scenes.push_back(notch_scene());
    for (glm::vec3& p : scenes.back().meshes[0].positions) p.y *= 1 + 0.01f * float(i);
  }
  PmiCache cache;
  for (int pass = 0; pass < 2; ++pass)
    for (const Scene& s : scenes) cache.get(s, ps);
  EXPECT_EQ(cache.misses(), 8u);
  const std::size_t one = pmi_maps_bytes(*cache.get(scenes[0], ps));
  PmiCache small(one * 3 / 2);
  for (int pass = 0; pass < 2; ++pass)
    for (const Scene& s : scenes) small.get(s, ps);
  EXPECT_EQ(small.misses(), 16u);
  small.get(scenes.back(), ps);
  EXPECT_EQ(small.misses(), 16u);
  // Room for two: the least recently used goes, and what is dropped is no longer counted.
  PmiCache two(one * 5 / 2);
  for (int i : {0, 1, 0, 2, 0, 1, 2, 1}) two.get(scenes[std::size_t(i)], ps);
  EXPECT_EQ(two.misses(), 5u);  // 0, 1, 2 (drops 1), 1 (drops 2), 2 (drops 0); 8 if the dropped
                                // stayed counted
  PmiCache none(1);             // under one map: the newest is still kept
  none.get(scenes[0], ps), none.get(scenes[0], ps);
  EXPECT_EQ(none.misses(), 1u);
}

TEST(Pmi, GivenVertexValuesAreDrawnInstead) {
  const Scene s = notch_scene();
  const RenderSettings rs = unblurred_pmi();
  PmiMaps half = uniform_maps(s, 0.5f);
  EXPECT_GT(pixels_at(shared_renderer().render(s, s.views[0], rs, &half).ao, 0.5f), 100);
  half.vertex_visibility.pop_back();
  EXPECT_THROW(shared_renderer().render(s, s.views[0], rs, &half), std::invalid_argument);
}

// The map `aosuite tune` fits (pmi_ao.frag): visibility v drawn as
// (1 - intensity (1 - v))^contrast, clamped to [0, 1]; the ground stays 1 whatever the map.
TEST(Pmi, IntensityAndContrastMapTheVisibility) {
  const Scene s = notch_scene();
  RenderSettings rs = unblurred_pmi();
  const PmiMaps maps = uniform_maps(s, 0.6f);
  struct Case {
    float intensity, contrast, want;
  };
  for (const Case c : {Case{1, 1, 0.6f}, Case{0.5f, 2, 0.64f}, Case{2, 0.5f, 0.4472136f},
                       Case{3, 2, 0.0f}, Case{-1, 3, 1.0f}}) {
    rs.params.intensity = c.intensity, rs.params.contrast = c.contrast;
    EXPECT_GT(pixels_at(shared_renderer().render(s, s.views[0], rs, &maps).ao, c.want), 100)
        << c.intensity << " " << c.contrast;
  }
}

TEST(Pmi, ParametersAreValidated) {
  RenderSettings s;
  s.width = 64, s.height = 48, s.technique = Technique::kPmi,
  s.params = default_params(s.technique);
  set_param(s.params, "viewpoints", "100");
  const Scene n = notch_scene();
  EXPECT_THROW(shared_renderer().render(n, n.views[0], s), std::invalid_argument);
  set_param(s.params, "viewpoints", "12");
  EXPECT_THROW(set_param(s.params, "pmi_resolution", "4"), std::invalid_argument);
  s.params.pmi.resolution = 4;  // set in code, past set_param: the renderer still refuses it
  EXPECT_THROW(shared_renderer().render(n, n.views[0], s), std::invalid_argument);
  EXPECT_EQ(parse_technique("pmi"), Technique::kPmi);
  EXPECT_EQ(technique_name(Technique::kPmi), "pmi");
}

}  // namespace
}  // namespace aosuite::renderer

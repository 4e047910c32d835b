// The depth-only G-buffer (issue 44's measurement, DepthGBufferPass): its linear depth and its
// normals reconstructed from depth must match the full G-buffer pass's wherever the surface
// is smooth, so render_bench's cost comparison compares like with like.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "renderer/passes/gbuffer_pass.hpp"
#include "renderer/renderer.hpp"

namespace aosuite::renderer {
namespace {

// One GL context for the whole program.
Renderer& shared_renderer() {
  static Renderer r;
  return r;
}

template <typename T>
std::vector<T> read(const Texture& t, GLenum format, int w, int h) {
  std::vector<T> v(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  glGetTextureImage(t.get(), 0, format, GL_FLOAT, static_cast<GLsizei>(v.size() * sizeof(T)),
                    v.data());
  return v;
}

// The angle between two normals stored as RGBA16F, whose lengths are 1 only to about 1e-3:
// atan2 of |a x b| and a . b, since acos of their dot product would read that as 2 degrees.
// A missing normal (zero) is 180 degrees from any.
double angle_degrees(glm::vec3 a, glm::vec3 b) {
  if (glm::dot(a, a) < 0.5f || glm::dot(b, b) < 0.5f) return 180;
  return glm::degrees(std::atan2(double(glm::length(glm::cross(a, b))), double(glm::dot(a, b))));
}

struct Comparison {
  std::vector<double> degrees;  // normal turn per geometry pixel
  double worst_depth = 0;       // relative linear-depth difference
  int sky_mismatches = 0;
};

Comparison compare_gbuffers(const char* scene_name, std::size_t view, int w, int h) {
  shared_renderer();  // makes the GL context current
  const Scene scene = builtin_scene(scene_name);
  const GpuScene gpu(scene);
  const Camera camera = make_camera(scene.views.at(view), w, h);
  const GBuffer g = make_gbuffer(w, h);
  GBufferPass full;
  full.run(gpu, camera, g);
  const auto depth = read<float>(g.depth, GL_RED, w, h);
  const auto normal = read<glm::vec4>(g.normal, GL_RGBA, w, h);
  DepthGBufferPass depth_only;
  depth_only.run(gpu, camera, g);
  const auto depth2 = read<float>(g.depth, GL_RED, w, h);
  const auto normal2 = read<glm::vec4>(g.normal, GL_RGBA, w, h);
  Comparison c;
  for (std::size_t i = 0; i < depth.size(); ++i) {
    EXPECT_TRUE(std::isfinite(depth2[i]) && std::isfinite(normal2[i].x) &&
                std::isfinite(normal2[i].y) && std::isfinite(normal2[i].z));
    if ((depth[i] > 0) != (depth2[i] > 0)) ++c.sky_mismatches;
    if (depth[i] <= 0 || depth2[i] <= 0) continue;
    c.worst_depth = std::max(c.worst_depth, std::abs(depth2[i] - depth[i]) / double(depth[i]));
    c.degrees.push_back(angle_degrees(glm::vec3(normal[i]), glm::vec3(normal2[i])));
  }
  return c;
}

double quantile(std::vector<double> v, double q) {
  auto at = v.begin() + static_cast<std::ptrdiff_t>(static_cast<double>(v.size() - 1) * q);
  std::nth_element(v.begin(), at, v.end());
  return *at;
}

// A plane seen at a slant is one flat surface: every reconstructed normal is its normal, up to
// the depth buffer's float rounding, the image's border pixels too (they have a neighbour on
// one side only).
TEST(DepthGBuffer, PlaneNormalsAndDepthMatchTheRasterisedOnes) {
  const Comparison c = compare_gbuffers("plane", 0, 160, 90);
  ASSERT_GT(c.degrees.size(), 1000u);
  EXPECT_EQ(c.sky_mismatches, 0);
  EXPECT_LT(c.worst_depth, 1e-5);
  EXPECT_LT(quantile(c.degrees, 1.0), 0.1);
}

// On curved and creased geometry only silhouettes and creases may turn: most pixels stay
// within a degree (facets of the tessellated spheres), and the median far below it.
TEST(DepthGBuffer, CurvedSceneNormalsStayCloseAwayFromEdges) {
  for (const char* name : {"spheres", "corner", "village"}) {
    const Comparison c = compare_gbuffers(name, 0, 320, 180);
    ASSERT_GT(c.degrees.size(), 1000u) << name;
    EXPECT_EQ(c.sky_mismatches, 0) << name;
    EXPECT_LT(c.worst_depth, 1e-5) << name;
    EXPECT_LT(quantile(c.degrees, 0.5), 1.0) << name;
    EXPECT_LT(quantile(c.degrees, 0.9), 5.0) << name;
  }
}

TEST(DepthGBuffer, NamesParseBack) {
  for (GBufferKind g : {GBufferKind::kFull, GBufferKind::kDepth})
    EXPECT_EQ(parse_gbuffer(gbuffer_name(g)), g);
  EXPECT_THROW(parse_gbuffer("normals"), std::invalid_argument);
}

// A frame over the depth-only G-buffer: its two passes are timed as the G-buffer's, its AO
// stays close to the full G-buffer's for every screen-space technique (the estimators see the
// same depths and nearly the same normals), with no NaN, and its lit images carry no colour.
TEST(DepthGBuffer, FramesOverItMatchTheFullGBuffersAo) {
  Renderer& r = shared_renderer();
  const Scene village = builtin_scene("village");
  for (const TechniqueInfo& t : techniques()) {
    if (!t.make_compute_pass) continue;  // screen-space techniques only
    RenderSettings s;
    s.width = 160, s.height = 90, s.technique = t.id, s.params = default_params(t.id);
    const Images full = r.render(village, village.views[0], s);
    s.gbuffer = GBufferKind::kDepth;
    const Images depth = r.render(village, village.views[0], s);
    ASSERT_EQ(cv::countNonZero(depth.ao != depth.ao), 0) << t.name << ": NaN";
    double sum = 0;
    for (int i = 0; i < full.ao.rows * full.ao.cols; ++i) {
      const double d = full.ao.ptr<float>()[i] - depth.ao.ptr<float>()[i];
      sum += d * d;
    }
    EXPECT_LT(std::sqrt(sum / (full.ao.rows * full.ao.cols)), 0.03) << t.name;
    std::vector<std::string> passes;
    for (const PassTime& p : depth.times) passes.push_back(p.pass);
    EXPECT_EQ(passes.at(0), "gbuffer") << t.name;
    EXPECT_EQ(passes.at(1), "gbuffer_normals") << t.name;
    // Untextured: every geometry pixel of no_ao is grey (R = G = B).
    cv::Mat channels[4];
    cv::split(depth.no_ao, channels);
    EXPECT_EQ(cv::countNonZero((channels[0] != channels[1]) & (depth.depth > 0)), 0) << t.name;
  }
}

}  // namespace
}  // namespace aosuite::renderer

// The ray-traced reference against closed-form AO, its noise against the i.i.d. bound, the
// G-buffer reconstruction against the camera, and the error metrics on known answers.
#include <gtest/gtest.h>

#include <cmath>

#include "png_fixture.hpp"
#include "reference/error_metrics.hpp"
#include "reference/frame_error.hpp"
#include "reference/reference_ao.hpp"
#include "reference/reference_cache.hpp"
#include "renderer/renderer.hpp"

namespace aosuite::reference {
namespace {

namespace rd = aosuite::renderer;
constexpr glm::vec3 kUp{0, 1, 0};
constexpr glm::vec3 kGrey{0.7f};

rd::Renderer& shared_renderer() {
  static rd::Renderer r;
  return r;
}

rd::Mesh floor_quad(float half = 200) {
  return rd::make_quad({-half, 0, -half}, {0, 0, 2 * half}, {2 * half, 0, 0}, kGrey);
}
// The plane x = 0 from y = 0 to y = height, 400 long in z (infinite as seen from |z| << 200).
rd::Mesh wall(float height) {
  return rd::make_quad({0, 0, -200}, {0, height, 0}, {0, 0, 400}, kGrey);
}

rd::Scene scene_of(std::initializer_list<rd::Mesh> meshes) {
  rd::Scene s;
  s.name = "test";
  s.meshes = meshes;
  return s;
}

float at(const EmbreeScene& scene, glm::vec3 p, int rays, float radius, Variant v,
         std::uint64_t key = 7) {
  return occlusion_at(scene, p + 1e-4f * kUp, kUp, key, {rays, radius, v});
}

// A floor point at distance d from a wall x = 0 of height h (infinite along z), unbounded rays.
// In the cross-section the wall spans the angles from the normal between atan(d/h) (its top)
// and pi/2 (its foot); an infinitely long strip subtending (phi1, phi2) has the cosine-weighted
// form factor (sin phi2 - sin phi1) / 2, so F = (1 - d / sqrt(d^2 + h^2)) / 2 and
// A = 1 - F = (1 + d / sqrt(d^2 + h^2)) / 2. An infinite wall (h -> inf) gives 1/2 at any d.
double wall_ao(double d, double h) { return 0.5 * (1 + d / std::sqrt(d * d + h * h)); }

TEST(Reference, UnoccludedPlaneIsExactlyOne) {
  const EmbreeScene scene(scene_of({floor_quad()}));
  for (Variant v : {Variant::kAo, Variant::kObscurance, Variant::kUnbounded}) {
    for (float x : {-10.0f, 0.0f, 3.5f}) {
      EXPECT_EQ(at(scene, {x, 0, 1}, 256, 1, v), 1.0f) << variant_name(v);
    }
  }
}

TEST(Reference, ConcaveCornerMatchesTheClosedForm) {
  // Tolerance 0.01: 4096 rays (i.i.d. spread <= 0.008; the stratified directions do better).
  const EmbreeScene crease(scene_of({floor_quad(), wall(200)}));
  EXPECT_NEAR(at(crease, {1e-3f, 0, 0}, 4096, 1, Variant::kUnbounded), 0.5, 0.01);
  EXPECT_NEAR(at(crease, {2, 0, 0}, 4096, 1, Variant::kUnbounded), wall_ao(2, 200), 0.01);
  const EmbreeScene low_wall(scene_of({floor_quad(), wall(1)}));
  for (double d : {0.25, 1.0, 3.0}) {
    EXPECT_NEAR(at(low_wall, {static_cast<float>(d), 0, 0}, 4096, 1, Variant::kUnbounded),
                wall_ao(d, 1), 0.01)
        << "d = " << d;
  }
}

TEST(Reference, RadiusBoundsTheRays) {
  // Under a ceiling at height h a ray at angle theta hits at h / cos(theta); with radius r it
  // counts only when cos(theta) > h / r, which cosine-weighted directions pick with
  // probability 1 - (h/r)^2, so A = (h/r)^2. Unbounded, every ray hits: A = 0.
  const float h = 0.6f;
  const EmbreeScene scene(
      scene_of({floor_quad(), rd::make_quad({-200, h, -200}, {400, 0, 0}, {0, 0, 400}, kGrey)}));
  EXPECT_NEAR(at(scene, {0, 0, 0}, 4096, 1, Variant::kAo), 0.36, 0.01);
  EXPECT_EQ(at(scene, {0, 0, 0}, 4096, 0.5f, Variant::kAo), 1.0f);  // r < h: nothing in reach
  EXPECT_LT(at(scene, {0, 0, 0}, 4096, 1, Variant::kUnbounded), 1e-3);
  // Obscurance weighs a hit at L by 1 - (1 - (L/r)^2)^3 >= 0, so it is never darker than AO.
  EXPECT_GT(at(scene, {0, 0, 0}, 4096, 1, Variant::kObscurance), 0.36 + 0.05);
}

TEST(Reference, SphereOnAPlane) {
  // A sphere of radius R resting on the floor, seen from a floor point at distance rho from the
  // contact point: the sphere lies wholly above the horizon (its cone just touches it), so its
  // form factor is cos(beta) (R/D)^2 with D^2 = R^2 + rho^2 and cos(beta) = R/D:
  // A = 1 - R^3 / (R^2 + rho^2)^(3/2); 0 at the contact point. Tolerance 0.015: 4096 rays and
  // a 96-segment sphere (inscribed, so slightly smaller than R).
  const EmbreeScene scene(scene_of({floor_quad(), rd::make_sphere({0, 1, 0}, 1, 96, kGrey)}));
  for (double rho : {0.35, 0.7, 1.5, 3.0}) {
    const double expected = 1 - 1 / std::pow(1 + rho * rho, 1.5);
    EXPECT_NEAR(at(scene, {static_cast<float>(rho), 0, 0}, 4096, 1e3f, Variant::kAo), expected,
                0.015)
        << "rho = " << rho;
  }
}

TEST(Reference, SpreadAcrossPixelsIsWithinTheIidBound) {
  // A = (0.5 / 0.7071)^2 = 0.5 under the ceiling everywhere, so the spread over 1024 points is
  // the estimator's: at most sqrt(A(1-A)/N) = 0.0625 for N = 64 (the i.i.d. value; stratified
  // directions are below it), and not zero (each point's rotation differs). Mean within 0.005.
  const float h = 0.5f, r = 0.70710678f;
  const EmbreeScene scene(
      scene_of({floor_quad(), rd::make_quad({-200, h, -200}, {400, 0, 0}, {0, 0, 400}, kGrey)}));
  constexpr int kRays = 64;
  double sum = 0, sq = 0;
  int n = 0;
  for (int i = 0; i < 32; ++i) {
    for (int j = 0; j < 32; ++j, ++n) {
      const glm::vec3 p{0.1f * static_cast<float>(i), 0, 0.1f * static_cast<float>(j)};
      const double a = at(scene, p, kRays, r, Variant::kAo, static_cast<std::uint64_t>(n));
      sum += a, sq += a * a;
    }
  }
  const double mean = sum / n, sd = std::sqrt(sq / n - mean * mean);
  EXPECT_NEAR(mean, 0.5, 0.005);
  EXPECT_LE(sd, std::sqrt(0.25 / kRays));
  EXPECT_GT(sd, 0.05 * std::sqrt(0.25 / kRays));
}

rd::Images gbuffer(const rd::Scene& scene, const rd::View& view, int w, int h) {
  rd::RenderSettings s;
  s.width = w, s.height = h;
  s.outputs = rd::parse_outputs("ao_float");
  s.outputs.normal = true;
  return shared_renderer().render(scene, view, s);
}

TEST(Reference, ImageUsesTheRasterisedSurfacePoints) {
  // A floor and a wall of height 1 at x = 0, seen from above the floor: each floor pixel's
  // reference must equal the closed form at the world position the camera puts it at, so a
  // wrong pixel centre, row order, or view transform shows. Tolerance: mean |error| < 0.01 and
  // every floor pixel within 0.05 (256 rays).
  const rd::Scene scene = scene_of({floor_quad(), wall(1)});
  const rd::View view{"v", {4, 3, 2}, {1, 0, 0}, {0, 1, 0}, 60, 0.05f};
  constexpr int kW = 96, kH = 64;
  const rd::Images img = gbuffer(scene, view, kW, kH);
  const rd::Camera camera = rd::make_camera(view, kW, kH);
  const cv::Mat ao = reference_ao(EmbreeScene(scene), camera, img.depth, img.normal,
                                  {256, 1, Variant::kUnbounded}, 2);
  const glm::mat4 to_world = glm::inverse(camera.view);
  double total = 0;
  int floor_pixels = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const float z = img.depth.at<float>(y, x);
      if (!(z > 0)) {
        EXPECT_EQ(ao.at<float>(y, x), 1.0f);
        continue;
      }
      const glm::vec3 p(to_world * glm::vec4(rd::view_position(camera, x, y, z), 1));
      if (std::abs(p.y) > 1e-3f || p.x < 0.05f) continue;  // the wall, or the crease's pixels
      const double err = ao.at<float>(y, x) - wall_ao(p.x, 1);
      EXPECT_LT(std::abs(err), 0.05) << x << "," << y;
      total += std::abs(err), ++floor_pixels;
    }
  }
  ASSERT_GT(floor_pixels, kW * kH / 4);
  EXPECT_LT(total / floor_pixels, 0.01);
}

TEST(Reference, UnoccludedPlaneImageIsExactlyOne) {
  const rd::Scene plane = rd::builtin_scene("plane");
  const rd::Images img = gbuffer(plane, plane.views[0], 64, 48);
  const cv::Mat ao = reference_ao(EmbreeScene(plane), rd::make_camera(plane.views[0], 64, 48),
                                  img.depth, img.normal, {64, 10, Variant::kAo}, 2);
  EXPECT_EQ(cv::countNonZero(ao != 1.0f), 0);
  EXPECT_GT(cv::countNonZero(img.depth > 0), 64 * 48 / 3);
}

TEST(ReferenceCache, PruneDeletesTheLeastRecentlyUsedFirst) {
  test::TempDir dir;
  const auto now = std::filesystem::file_time_type::clock::now();
  for (int i = 0; i < 5; ++i) {  // 100 bytes each; file 0 used longest ago
    const auto file = dir / (std::to_string(i) + ".aoref");
    test::write_bytes(file, test::Bytes(100, 1));
    std::filesystem::last_write_time(file, now - std::chrono::minutes(10 - i));
  }
  test::write_bytes(dir / "notes.txt", test::Bytes(1000, 1));  // not a reference: kept
  EXPECT_EQ(prune_cache(dir.path(), 500, {}), 0);
  EXPECT_EQ(prune_cache(dir.path(), 250, dir / "0.aoref"), 3);  // 1, 2, 3 go; 0 is kept
  for (const char* gone : {"1.aoref", "2.aoref", "3.aoref"})
    EXPECT_FALSE(std::filesystem::exists(dir / gone)) << gone;
  for (const char* kept : {"0.aoref", "4.aoref", "notes.txt"})
    EXPECT_TRUE(std::filesystem::exists(dir / kept)) << kept;
}

TEST(ReferenceCache, StaysWithinItsLimitAndKeepsWhatWasJustUsed) {
  const rd::Scene plane = rd::builtin_scene("plane");
  const rd::Images img = gbuffer(plane, plane.views[0], 32, 24);
  const rd::Camera camera = rd::make_camera(plane.views[0], 32, 24);
  test::TempDir dir;
  const std::uint64_t one_file = 16 + 32 * 24 * 4;
  ReferenceCache cache(plane, dir.path(), one_file + one_file / 2);  // room for one
  auto get = [&](float radius) {
    return cache.get(camera, img.depth, img.normal, {16, radius, Variant::kAo});
  };
  get(1);
  EXPECT_FALSE(cache.last_was_cached());
  get(1);
  EXPECT_TRUE(cache.last_was_cached());
  get(2);  // a second reference pushes the first out
  get(2);
  EXPECT_TRUE(cache.last_was_cached());
  get(1);
  EXPECT_FALSE(cache.last_was_cached());
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(Reference, RejectsBadSettings) {
  const EmbreeScene scene(scene_of({floor_quad()}));
  const cv::Mat depth(4, 4, CV_32F, cv::Scalar(1)), normal(4, 4, CV_32FC3, cv::Scalar(0, 0, 1));
  const rd::View view;
  const rd::Camera camera = rd::make_camera(view, 4, 4);
  EXPECT_THROW(reference_ao(scene, camera, depth, normal, {0, 1, Variant::kAo}),
               std::invalid_argument);
  EXPECT_THROW(reference_ao(scene, camera, depth, normal, {16, NAN, Variant::kAo}),
               std::invalid_argument);
  EXPECT_THROW(reference_ao(scene, rd::make_camera(view, 5, 4), depth, normal, {}),
               std::invalid_argument);
  EXPECT_THROW(parse_variant("bent"), std::invalid_argument);
}

// Metrics on synthetic images: 40x30, geometry everywhere but a sky column at x < 10.
struct Synthetic {
  cv::Mat depth = cv::Mat(30, 40, CV_32F, cv::Scalar(2));
  cv::Mat reference = cv::Mat(30, 40, CV_32F, cv::Scalar(0.5));
  Synthetic() { depth.colRange(0, 10).setTo(0); }
};

TEST(ErrorMetrics, ConstantOffset) {
  const Synthetic s;
  const cv::Mat darker = s.reference - 0.1;
  const ErrorReport r = measure_error(darker, s.reference, s.depth, {2, 0.05f, 64});
  EXPECT_EQ(r.all.pixels, static_cast<std::size_t>((40 - 10 - 2) * (30 - 4)));
  EXPECT_NEAR(r.all.rmse, 0.1, 1e-6);
  EXPECT_NEAR(r.all.mae, 0.1, 1e-6);
  EXPECT_NEAR(r.all.bias, -0.1, 1e-6);
  EXPECT_NEAR(r.all.psnr, 20, 1e-4);
  EXPECT_NEAR(r.all.noise_floor, std::sqrt(0.25 / 64), 1e-9);
  EXPECT_LT(r.all.ssim, 1);
}

TEST(ErrorMetrics, SsimOfAnImageWithItselfIsOne) {
  Synthetic s;
  cv::randu(s.reference, 0, 1);
  const ErrorReport r = measure_error(s.reference, s.reference, s.depth);
  EXPECT_NEAR(r.all.ssim, 1, 1e-6);
  EXPECT_EQ(r.all.rmse, 0);
  EXPECT_EQ(r.all.psnr, HUGE_VAL);  // compare/metric.hpp's psnr_db: identical is +inf
  cv::Mat noisy = s.reference.clone();
  cv::randn(noisy, 0.5, 0.2);
  EXPECT_LT(measure_error(noisy, s.reference, s.depth).all.ssim, 0.5);
}

TEST(ErrorMetrics, MasksSplitEdgesFromInterior) {
  Synthetic s;
  s.depth.colRange(25, 40).setTo(4);  // a step at x = 25 and the sky's edge at x = 10
  const cv::Mat edges = depth_edge_mask(s.depth, 0.05f);
  EXPECT_EQ(cv::countNonZero(edges), 3 * 30);  // x = 10 (beside the sky), 24 and 25 (the step)
  const cv::Mat mask = geometry_mask(s.depth, 3);
  EXPECT_EQ(mask.at<unsigned char>(5, 20), 255);
  EXPECT_EQ(mask.at<unsigned char>(5, 5), 0);   // sky
  EXPECT_EQ(mask.at<unsigned char>(1, 20), 0);  // border
  cv::Mat est = s.reference.clone();
  est.col(24).setTo(0.0);  // error only on the step
  const ErrorReport r = measure_error(est, s.reference, s.depth, {3, 0.05f, 256});
  EXPECT_EQ(r.interior.rmse, 0);
  EXPECT_NEAR(r.edge.bias, -0.5 * (30 - 6) / static_cast<double>(r.edge.pixels), 1e-6);
  EXPECT_EQ(r.all.pixels, r.edge.pixels + r.interior.pixels);
}

TEST(ErrorMetrics, EveryTechniqueHasAFiniteErrorOnTheDefaultSuite) {
  // The default suite's scenes and views, small and with few rays: each metric finite.
  for (const char* name : {"plane", "corner", "spheres", "village", "workshop"}) {
    const rd::Scene scene = rd::builtin_scene(name);
    const EmbreeScene rt(scene);
    for (const rd::View& view : scene.views) {
      rd::RenderSettings s;
      s.width = 64, s.height = 36;
      s.outputs = rd::parse_outputs("ao_float");
      s.outputs.normal = true;
      for (const std::string& technique : rd::screen_space_technique_names()) {
        const rd::Technique t = rd::parse_technique(technique);
        s.technique = t, s.params = rd::default_params(t);
        const rd::Images img = shared_renderer().render(scene, view, s);
        const cv::Mat ref = reference_ao(rt, rd::make_camera(view, 64, 36), img.depth, img.normal,
                                         {16, s.params.radius, Variant::kAo}, 2);
        const ErrorReport r = measure_error(img.ao, ref, img.depth, {4, 0.05f, 16});
        for (const ErrorStats& e : {r.all, r.edge, r.interior}) {
          for (double v : {e.rmse, e.mae, e.bias, e.ssim, e.noise_floor})
            EXPECT_TRUE(std::isfinite(v))
                << name << " " << view.name << " " << rd::technique_name(t);
          // +inf exactly when the estimate is exact (the plane seen from above, often).
          EXPECT_TRUE(std::isfinite(e.psnr) || (e.psnr == HUGE_VAL && e.rmse == 0))
              << name << " " << view.name << " " << rd::technique_name(t);
        }
        EXPECT_GT(r.all.pixels, 0u) << name << " " << view.name;
      }
    }
  }
}

}  // namespace
}  // namespace aosuite::reference

namespace aosuite::reference {
namespace {

// A lit frame with sky on the left, and an AO term that darkens a square on the right.
struct Frame {
  cv::Mat no_ao{24, 32, CV_8UC4, cv::Scalar(180, 140, 90, 255)};
  cv::Mat depth{24, 32, CV_32F, cv::Scalar(1.0f)};
  cv::Mat ao{24, 32, CV_32F, cv::Scalar(1.0f)};
  Frame() {
    depth(cv::Rect(0, 0, 8, 24)).setTo(0.0f);
    no_ao(cv::Rect(0, 0, 8, 24)).setTo(cv::Scalar(158, 184, 219, 255));
  }
};

TEST(FrameError, ShadingMatchesTheBlendPass) {
  Frame f;
  f.ao.setTo(0.5f);
  const cv::Mat shaded = shade(f.no_ao, f.ao, f.depth);
  // Sky keeps its colour; geometry is lit * AO in linear light: 180 -> 0.456 linear -> 0.228
  // -> sRGB 0.5145 -> 131.
  EXPECT_EQ(shaded.at<cv::Vec4b>(5, 2), f.no_ao.at<cv::Vec4b>(5, 2));
  EXPECT_EQ(int(shaded.at<cv::Vec4b>(5, 20)[0]), 131);
  EXPECT_EQ(int(shaded.at<cv::Vec4b>(5, 20)[3]), 255);
  // AO 1 changes nothing.
  const cv::Mat unchanged = shade(f.no_ao, cv::Mat(24, 32, CV_32F, cv::Scalar(1.0f)), f.depth);
  EXPECT_EQ(cv::norm(unchanged, f.no_ao, cv::NORM_INF), 0.0);
}

TEST(FrameError, SameAoIsNoErrorAndMoreDarkeningIsMore) {
  Frame f;
  const FrameError same = frame_error(f.no_ao, f.ao, f.ao, f.depth);
  EXPECT_EQ(same.value("flip"), 0.0);
  EXPECT_EQ(same.value("ssim"), 1.0);
  EXPECT_EQ(same.value("rmse"), 0.0);
  EXPECT_EQ(same.values.size(), metric::all().size()) << "every registered metric";
  cv::Mat light = f.ao.clone(), dark = f.ao.clone();
  light(cv::Rect(16, 8, 8, 8)).setTo(0.8f);
  dark(cv::Rect(16, 8, 8, 8)).setTo(0.3f);
  const FrameError a = frame_error(f.no_ao, light, f.ao, f.depth);
  const FrameError b = frame_error(f.no_ao, dark, f.ao, f.depth);
  EXPECT_GT(a.value("flip"), 0.0);
  EXPECT_GT(b.value("flip"), a.value("flip"));
  EXPECT_LT(b.value("ssim"), a.value("ssim"));
  EXPECT_LT(a.value("ssim"), 1.0);
  EXPECT_GT(b.value("rmse"), a.value("rmse"));
  EXPECT_THROW(frame_error(f.no_ao, f.ao(cv::Rect(0, 0, 8, 8)).clone(), f.ao, f.depth),
               std::invalid_argument);
}

}  // namespace
}  // namespace aosuite::reference

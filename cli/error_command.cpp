// `aosuite error`: one technique's AO term (Images::ao, after its default blur) against the
// ray-traced reference at the technique's radius, on the same G-buffer pixels; prints RMSE,
// MAE, bias, PSNR and SSIM over all, depth-edge and interior pixels next to the reference's
// noise floor, the final image's FLIP and SSIM against the same frame shaded with the
// reference (reference/frame_error.hpp), and optionally writes the reference and an error
// heat map.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/gl_command_util.hpp"
#include "compare/opencv.hpp"
#include "reference/frame_error.hpp"
#include "reference/reference_cache.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::cli {
namespace {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;
namespace ref = aosuite::reference;

struct ErrorArgs {
  CaseOptions c;  // --radius is the reference's radius too
  std::string variant = "ao", out;
  int rays = 256;
  bool json = false;
};

cv::Mat grey_rgba(const cv::Mat& ao) {
  cv::Mat out(ao.size(), CV_8UC4);
  for (int y = 0; y < ao.rows; ++y) {
    for (int x = 0; x < ao.cols; ++x) {
      // saturate_cast rounds to nearest itself.
      const auto v = cv::saturate_cast<unsigned char>(ao.at<float>(y, x) * 255.0f);
      out.at<cv::Vec4b>(y, x) = {v, v, v, 255};
    }
  }
  return out;
}

// Signed error, technique - reference: red where the technique is too bright, blue where it is
// too dark, full colour at |error| >= 0.25; background black.
cv::Mat heat_map(const cv::Mat& estimate, const cv::Mat& reference, const cv::Mat& depth) {
  cv::Mat out(estimate.size(), CV_8UC4, cv::Scalar(0, 0, 0, 255));
  for (int y = 0; y < out.rows; ++y) {
    for (int x = 0; x < out.cols; ++x) {
      if (!(depth.at<float>(y, x) > 0)) continue;
      const float e = estimate.at<float>(y, x) - reference.at<float>(y, x);
      const auto s = cv::saturate_cast<unsigned char>(std::min(std::abs(e) / 0.25f, 1.0f) * 255);
      const auto rest = static_cast<unsigned char>(255 - s);
      out.at<cv::Vec4b>(y, x) =
          e > 0 ? cv::Vec4b{255, rest, rest, 255} : cv::Vec4b{rest, rest, 255, 255};
    }
  }
  return out;
}

void print_stats(const char* name, const ref::ErrorStats& s) {
  fmt::print("  {:<9} {:>9} {:>8.4f} {:>8.4f} {:>8.4f} {:>+8.4f} {:>7.2f} {:>7.4f}\n", name,
             s.pixels, s.rmse, s.noise_floor, s.mae, s.bias, s.psnr, s.ssim);
}

std::string frame_text(const ref::FrameError& e) {
  std::string out;
  for (const metric::Value& v : e.values) out += fmt::format(" {} {:.4f}", v.key, v.value);
  return out;
}

int run_error(const ErrorArgs& a) {
  const rd::Scene scene = rd::load_scene(a.c.scene);
  const rd::View& view = rd::find_view(scene, a.c.view);
  rd::RenderSettings s = case_settings(a.c);
  s.outputs = rd::parse_outputs("no_ao,ao_float");  // no_ao: the frame error's lighting
  s.outputs.normal = true;
  const ref::ReferenceSettings rs{a.rays, s.params.radius, ref::parse_variant(a.variant)};
  ref::validate(rs);

  rd::Renderer renderer;
  const rd::Images img = renderer.render(scene, view, s);
  ref::ReferenceCache cache(scene, ref::default_cache_dir());
  const rd::Camera camera = rd::make_camera(view, s.width, s.height);
  const cv::Mat reference = cache.get(camera, img.depth, img.normal, rs);
  const ref::ErrorReport r = ref::measure_error(img.ao, reference, img.depth, {8, 0.05f, rs.rays});
  const ref::FrameError frame = ref::frame_error(img.no_ao, img.ao, reference, img.depth);

  const std::string stem = fmt::format("{}_{}_{}", scene.name, view.name, a.c.technique);
  if (!a.out.empty()) {
    const fs::path dir(a.out);
    fs::create_directories(dir);
    write_exr(dir / (stem + "_reference.exr"), reference);
    write_png_rgba8(dir / (stem + "_reference.png"), grey_rgba(reference));
    write_png_rgba8(dir / (stem + "_ao.png"), grey_rgba(img.ao));
    write_png_rgba8(dir / (stem + "_error.png"), heat_map(img.ao, reference, img.depth));
  }
  if (a.json) {
    nlohmann::ordered_json j;
    j["scene"] = scene.name, j["view"] = view.name, j["technique"] = a.c.technique;
    j["width"] = s.width, j["height"] = s.height;
    j["samples"] = s.params.samples, j["radius"] = s.params.radius;
    j["intensity"] = s.params.intensity;
    j["reference"] = {{"variant", a.variant},
                      {"rays", rs.rays},
                      {"radius", rs.radius},
                      {"cached", cache.last_was_cached()},
                      {"seconds", cache.last_seconds()}};
    j["error"] = to_json(r);
    j["frame"] = to_json(frame);
    fmt::print("{}\n", j.dump(2));
    return kExitSame;
  }
  fmt::print("{} {}x{} s={} r={:g}: reference {} {} rays, {}\n", stem, s.width, s.height,
             s.params.samples, s.params.radius, a.variant, rs.rays,
             cache.last_was_cached() ? std::string("from cache")
                                     : fmt::format("traced in {:.1f} s", cache.last_seconds()));
  fmt::print("  {:<9} {:>9} {:>8} {:>8} {:>8} {:>8} {:>7} {:>7}\n", "", "pixels", "RMSE", "noise",
             "MAE", "bias", "PSNR", "SSIM");
  print_stats("all", r.all);
  print_stats("edge", r.edge);
  print_stats("interior", r.interior);
  fmt::print("  final image against the same frame shaded with the reference:{}\n",
             frame_text(frame));
  return kExitSame;
}

}  // namespace

void add_error_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<ErrorArgs>();
  CLI::App* cmd =
      app.add_subcommand("error", "Measure a technique's AO against a ray-traced reference");
  add_case_options(cmd, a->c);
  cmd->add_option("--rays", a->rays, "reference rays per pixel")->capture_default_str();
  cmd->add_option("--variant", a->variant, "reference: ao|obscurance|unbounded")
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "print the metrics as JSON");
  cmd->add_option("--out", a->out, "write the reference (EXR, PNG), the AO and an error heat map");
  guarded(cmd, rc, "error", [a] { return run_error(*a); });
}

}  // namespace aosuite::cli

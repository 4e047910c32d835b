// `aosuite error`: one technique's AO term against the ray-traced reference at the technique's
// radius (ao/error_study.hpp); prints RMSE, MAE, bias, PSNR and SSIM over all, depth-edge and
// interior pixels next to the reference's noise floor, and the final image's FLIP and SSIM,
// and optionally writes the reference and an error heat map.
#include <fmt/format.h>

#include <filesystem>

#include "ao/error_images.hpp"
#include "ao/error_study.hpp"
#include "cli/commands.hpp"
#include "cli/gl_command_util.hpp"
#include "compare/opencv.hpp"

namespace aosuite::cli {
namespace {

namespace fs = std::filesystem;
namespace ref = aosuite::reference;

struct ErrorArgs {
  ao::CaseOptions c;  // --radius is the reference's radius too
  std::string variant = "ao", out;
  int rays = 256;
  bool json = false;
};

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
  const ao::ErrorStudy e = ao::measure_error_study(a.c, a.variant, a.rays);
  const std::string stem = fmt::format("{}_{}_{}", e.scene, e.view, a.c.technique);
  if (!a.out.empty()) {
    const fs::path dir(a.out);
    fs::create_directories(dir);
    write_exr(dir / (stem + "_reference.exr"), e.reference);
    write_png_rgba8(dir / (stem + "_reference.png"), ao::grey_rgba(e.reference));
    write_png_rgba8(dir / (stem + "_ao.png"), ao::grey_rgba(e.ao));
    write_png_rgba8(dir / (stem + "_error.png"), ao::heat_map(e.ao, e.reference, e.depth));
  }
  if (a.json) {
    fmt::print("{}\n", ao::error_study_json(e, a.c, a.variant).dump(2));
    return kExitSame;
  }
  const renderer::RenderSettings& s = e.settings;
  fmt::print("{} {}x{} s={} r={:g}: reference {} {} rays, {}\n", stem, s.width, s.height,
             s.params.samples, s.params.radius, a.variant, e.reference_settings.rays,
             e.reference_cached ? std::string("from cache")
                                : fmt::format("traced in {:.1f} s", e.reference_seconds));
  fmt::print("  {:<9} {:>9} {:>8} {:>8} {:>8} {:>8} {:>7} {:>7}\n", "", "pixels", "RMSE", "noise",
             "MAE", "bias", "PSNR", "SSIM");
  print_stats("all", e.error.all);
  print_stats("edge", e.error.edge);
  print_stats("interior", e.error.interior);
  fmt::print("  final image against the same frame shaded with the reference:{}\n",
             frame_text(e.frame));
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

#include "cli/gl_command_util.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <system_error>

#include "compare/exr_file.hpp"
#include "compare/image_io.hpp"
#include "renderer/params.hpp"

namespace aosuite::cli {

namespace rd = aosuite::renderer;
namespace fs = std::filesystem;

rd::AoParams technique_params(rd::Technique t, const std::optional<std::string>& samples,
                              const std::optional<std::string>& radius,
                              const std::vector<std::string>& params) {
  rd::AoParams p = rd::default_params(t);
  if (samples) rd::set_param(p, "samples", *samples);
  if (radius) rd::set_param(p, "radius", *radius);
  for (const std::string& kv : params) {
    const std::size_t eq = kv.find('=');
    if (eq == std::string::npos) {
      throw std::invalid_argument(fmt::format("--param '{}': expected KEY=VALUE", kv));
    }
    rd::set_param(p, kv.substr(0, eq), kv.substr(eq + 1));
  }
  return p;
}

void add_case_options(CLI::App* cmd, CaseOptions& o) {
  cmd->add_option("--scene", o.scene,
                  "built-in scene name or scene file (.toml); `aosuite scenes` lists them")
      ->capture_default_str();
  cmd->add_option("--view", o.view, "view name or index (default: the first)");
  cmd->add_option("--technique", o.technique, rd::technique_names("|"))->capture_default_str();
  cmd->add_option("--width", o.width)->capture_default_str();
  cmd->add_option("--height", o.height)->capture_default_str();
  cmd->add_option("--samples", o.samples, "samples per pixel (default: the technique's)");
  cmd->add_option("--radius", o.radius, "radius in scene units");
  std::string keys;
  for (const rd::ParamSpec& p : rd::param_specs()) keys += fmt::format("\n  {}: {}", p.key, p.doc);
  cmd->add_option("--param", o.params, "KEY=VALUE, repeatable; keys:" + keys);
}

rd::RenderSettings case_settings(const CaseOptions& o) {
  rd::RenderSettings s;
  s.width = o.width, s.height = o.height;
  s.technique = rd::parse_technique(o.technique);
  s.params = technique_params(s.technique, o.samples, o.radius, o.params);
  return s;
}

void write_exr(const fs::path& path, const cv::Mat& image) {
  CV_Assert(image.type() == CV_32FC1 && image.isContinuous());
  aosuite::write_exr(path, image.cols, image.rows, image.ptr<float>());
}

nlohmann::ordered_json params_json(rd::Technique technique, const rd::AoParams& p) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const rd::ParamSpec& spec : rd::param_specs()) {
    if (!rd::applies(spec, technique)) continue;
    std::visit([&](const auto& v) { j[std::string(spec.key)] = v; }, rd::param_value(spec, p));
  }
  return j;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

nlohmann::ordered_json to_json(const reference::ErrorStats& s) {
  return {{"pixels", s.pixels},
          {"rmse", s.rmse},
          {"mae", s.mae},
          {"bias", s.bias},
          {"psnr", s.psnr},
          {"ssim", s.ssim},
          {"noise_floor", s.noise_floor}};
}

nlohmann::ordered_json to_json(const reference::ErrorReport& r) {
  return {{"all", to_json(r.all)}, {"edge", to_json(r.edge)}, {"interior", to_json(r.interior)}};
}

reference::ErrorStats error_stats_from_json(const nlohmann::json& j) {
  reference::ErrorStats s;
  s.pixels = j.at("pixels"), s.rmse = j.at("rmse"), s.mae = j.at("mae"), s.bias = j.at("bias");
  // JSON has no infinity: an exact estimate's PSNR is kept as null (psnr_db's +inf).
  const nlohmann::json& psnr = j.at("psnr");
  s.psnr = psnr.is_null() ? HUGE_VAL : psnr.get<double>();
  s.ssim = j.at("ssim"), s.noise_floor = j.at("noise_floor");
  return s;
}

reference::ErrorReport error_report_from_json(const nlohmann::json& j) {
  return {error_stats_from_json(j.at("all")), error_stats_from_json(j.at("edge")),
          error_stats_from_json(j.at("interior"))};
}

}  // namespace aosuite::cli

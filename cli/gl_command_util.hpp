// What several OpenGL commands share: technique parameters from options, float EXR output,
// medians of timed runs, and error metrics as JSON.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "reference/error_metrics.hpp"
#include "renderer/renderer.hpp"
#include "renderer/technique.hpp"

namespace aosuite::cli {

// What `render` and `error` both take: which case to draw and with which parameters.
struct CaseOptions {
  std::string scene = "village", view, technique = "alchemy";
  int width = 1920, height = 1080;
  std::optional<std::string> samples, radius;
  std::vector<std::string> params;  // KEY=VALUE
};
// --scene, --view, --technique, --width, --height, --samples, --radius, --param.
void add_case_options(CLI::App* cmd, CaseOptions& o);
// The render settings they name (all outputs, as RenderSettings defaults); throws
// std::invalid_argument for an unknown technique or a bad parameter.
renderer::RenderSettings case_settings(const CaseOptions& o);

// The technique's defaults, then --samples, --radius and each --param KEY=VALUE in order.
// Throws std::invalid_argument for a malformed pair or a bad value.
renderer::AoParams technique_params(renderer::Technique t,
                                    const std::optional<std::string>& samples,
                                    const std::optional<std::string>& radius,
                                    const std::vector<std::string>& params);

// A CV_32F single-channel image as float EXR, written atomically; throws FileError.
void write_exr(const std::filesystem::path& path, const cv::Mat& image);

double median(std::vector<double> v);

// The parameters `technique` reads, with their types (parameter table order).
nlohmann::ordered_json params_json(renderer::Technique technique, const renderer::AoParams& p);

nlohmann::ordered_json to_json(const reference::ErrorStats& s);
nlohmann::ordered_json to_json(const reference::ErrorReport& r);
// Their inverses; nlohmann::json's errors for a missing or mistyped key.
reference::ErrorStats error_stats_from_json(const nlohmann::json& j);
reference::ErrorReport error_report_from_json(const nlohmann::json& j);

}  // namespace aosuite::cli

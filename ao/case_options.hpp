// Which case `render` and `error` draw and with which parameters, as their options give it,
// and the render settings that names. (The options themselves are the CLI's.)
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "renderer/renderer.hpp"
#include "renderer/technique.hpp"

namespace aosuite::ao {

struct CaseOptions {
  std::string scene = "village", view, technique = "alchemy";
  int width = 1920, height = 1080;
  std::optional<std::string> samples, radius;
  std::vector<std::string> params;  // KEY=VALUE
  std::string preset;    // a preset file or built-in name (ao/preset.hpp), applied before the above
  std::string pipeline;  // fragment|compute; empty: the device's default
  std::string gbuffer = "full";  // full|depth
};

// The render settings they name (all outputs, as RenderSettings defaults); throws
// std::invalid_argument for an unknown technique or pipeline, or a bad parameter.
renderer::RenderSettings case_settings(const CaseOptions& o);

// The parameters `technique` reads, with their types (parameter table order): what `render`
// and `error` report they used, and what a preset holds.
nlohmann::ordered_json params_json(renderer::Technique technique, const renderer::AoParams& p);

}  // namespace aosuite::ao

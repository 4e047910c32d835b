#include "ao/case_options.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <variant>

#include "ao/preset.hpp"
#include "renderer/params.hpp"

namespace aosuite::ao {

namespace {

namespace rd = aosuite::renderer;

// The technique's defaults, then the preset, --samples, --radius and each --param KEY=VALUE
// in order. Throws std::invalid_argument for a malformed pair or a bad value, FileError for a
// bad preset file.
rd::AoParams technique_params(rd::Technique t, const std::string& preset,
                              const std::optional<std::string>& samples,
                              const std::optional<std::string>& radius,
                              const std::vector<std::string>& params) {
  rd::AoParams p = rd::default_params(t);
  if (!preset.empty()) apply_preset(find_preset(preset, t), t, p);
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

}  // namespace

rd::RenderSettings case_settings(const CaseOptions& o) {
  rd::RenderSettings s;
  s.width = o.width, s.height = o.height;
  s.technique = rd::parse_technique(o.technique);
  s.params = technique_params(s.technique, o.preset, o.samples, o.radius, o.params);
  if (!o.pipeline.empty()) s.pipeline = rd::parse_pipeline(o.pipeline);
  s.gbuffer = rd::parse_gbuffer(o.gbuffer);
  return s;
}

nlohmann::ordered_json params_json(rd::Technique technique, const rd::AoParams& p) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const rd::ParamSpec& spec : rd::param_specs()) {
    if (!rd::applies(spec, technique)) continue;
    std::visit([&](const auto& v) { j[std::string(spec.key)] = v; }, rd::param_value(spec, p));
  }
  return j;
}

}  // namespace aosuite::ao

#include "ao/sweep_rows.hpp"

#include <fmt/format.h>

#include "ao/error_json.hpp"

namespace aosuite::ao {

namespace rd = aosuite::renderer;
namespace ref = aosuite::reference;

std::string params_text(const Row& r) {
  std::string out;
  for (const auto& [k, v] : r.params) out += (out.empty() ? "" : " ") + k + "=" + v;
  return out;
}

std::string row_label(const Row& r) {
  const std::string name(rd::technique_name(r.technique));
  return r.params.empty() ? name : fmt::format("{} ({})", name, params_text(r));
}

nlohmann::ordered_json row_json(const Row& r, bool unbounded) {
  nlohmann::ordered_json j{{"index", r.index},
                           {"scene", r.scene},
                           {"view", r.view},
                           {"view_index", r.view_index},
                           {"technique", rd::technique_name(r.technique)},
                           {"width", r.width},
                           {"height", r.height},
                           {"samples", r.samples},
                           {"radius", r.radius},
                           {"intensity", r.intensity},
                           {"params", r.params},
                           {"ao_gl_ms", r.gl_ms},
                           {"geometry_pixels", r.geometry_pixels},
                           {"error", to_json(r.error)},
                           {"frame", to_json(r.frame)}};
  if (unbounded) j["error_unbounded"] = to_json(r.unbounded);
  return j;
}

Row row_from_json(const nlohmann::json& j) {
  Row r;
  r.index = j.at("index"), r.scene = j.at("scene"), r.view = j.at("view");
  r.view_index = j.at("view_index");
  r.technique = rd::parse_technique(j.at("technique").get<std::string>());
  r.width = j.at("width"), r.height = j.at("height"), r.samples = j.at("samples");
  r.radius = j.at("radius"), r.intensity = j.at("intensity");
  r.params = j.at("params").get<std::map<std::string, std::string>>();
  r.gl_ms = j.at("ao_gl_ms");
  r.geometry_pixels = j.value("geometry_pixels", -1);  // -1: a row written before it was kept
  r.error = error_report_from_json(j.at("error"));
  r.frame = ref::frame_error_from_json(j.at("frame"));
  if (j.contains("error_unbounded")) r.unbounded = error_stats_from_json(j.at("error_unbounded"));
  return r;
}

}  // namespace aosuite::ao

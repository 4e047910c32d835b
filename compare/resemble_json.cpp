#include "compare/resemble_json.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "compare/js_number.hpp"

namespace aosuite::resemble {

std::string result_json(const Result& r, const nlohmann::ordered_json& extra) {
  const Bounds& b = r.diff_bounds;
  std::string out =
      fmt::format(R"({{"misMatchPercentage":"{}","rawMisMatchPercentage":{},"isSameDimensions":{},)"
                  R"("dimensionDifference":{{"width":{},"height":{}}},)"
                  R"("diffBounds":{{"top":{},"left":{},"bottom":{},"right":{}}},"analysisTime":{})",
                  r.mismatch_percentage, js_number_to_string(r.raw_mismatch_percentage),
                  r.same_dimensions, r.width_difference, r.height_difference, b.top, b.left,
                  b.bottom, b.right, static_cast<long long>(std::llround(r.analysis_ms)));
  if (extra.is_object()) {
    for (const auto& [key, value] : extra.items()) {
      out += fmt::format(",{}:{}", nlohmann::json(key).dump(), value.dump());
    }
  }
  return out + "}";
}

namespace {

double number(const nlohmann::json& j, const char* key) {
  if (!j.is_number()) throw std::invalid_argument(fmt::format("'{}' must be a number", key));
  return j.get<double>();
}

double field(const nlohmann::json& obj, const char* key, double fallback) {
  const auto it = obj.find(key);
  return it == obj.end() || it->is_null() ? fallback : number(*it, key);
}

std::vector<Box> boxes(const nlohmann::json& j, const char* key) {
  if (!j.is_array()) throw std::invalid_argument(fmt::format("'{}' must be an array", key));
  std::vector<Box> out;
  for (const auto& b : j) {
    if (!b.is_object()) throw std::invalid_argument(fmt::format("'{}' holds a non-object", key));
    out.push_back(
        {field(b, "left", 0), field(b, "top", 0), field(b, "right", 0), field(b, "bottom", 0)});
  }
  return out;
}

void require_object(const nlohmann::json& j, const char* key) {
  if (!j.is_object()) throw std::invalid_argument(fmt::format("'{}' must be an object", key));
}

// A key of Resemble's `tolerance` object, when present, replaces the mode's value.
void take_override(const nlohmann::json& obj, const char* key, std::optional<double>& value) {
  if (obj.contains(key)) value = number(obj.at(key), key);
}

}  // namespace

void apply_json_options(const nlohmann::json& j, Options& o) {
  if (!j.is_object()) throw std::invalid_argument("options must be a JSON object");
  for (const auto& [key, v] : j.items()) {
    if (key == "mode") {
      if (!v.is_string()) throw std::invalid_argument("'mode' must be a string");
      o.modes = {parse_mode(v.get<std::string>())};
    } else if (key == "largeImageThreshold") {
      o.large_image_threshold = number(v, "largeImageThreshold");
    } else if (key == "errorType") {
      if (!v.is_string()) throw std::invalid_argument("'errorType' must be a string");
      o.error_type = parse_error_type(v.get<std::string>());
    } else if (key == "errorColor") {
      require_object(v, "errorColor");
      const Color& e = o.error_color;
      o.error_color = {field(v, "red", e.r), field(v, "green", e.g), field(v, "blue", e.b),
                       field(v, "alpha", e.a)};
    } else if (key == "transparency") {
      if (v.is_number()) o.transparency = v.get<double>();  // Resemble ignores non-numbers
    } else if (key == "boundingBoxes") {
      o.bounding_boxes = boxes(v, "boundingBoxes");
    } else if (key == "ignoredBoxes") {
      o.ignored_boxes = boxes(v, "ignoredBoxes");
    } else if (key == "ignoreAreasColoredWith") {
      require_object(v, "ignoreAreasColoredWith");
      o.ignore_areas_colored_with =
          Color{field(v, "r", NAN), field(v, "g", NAN), field(v, "b", NAN), field(v, "a", 255)};
    } else if (key == "returnEarlyThreshold") {
      o.return_early_threshold = number(v, "returnEarlyThreshold");
    } else if (key == "tolerance") {
      require_object(v, "tolerance");
      take_override(v, "red", o.tolerance.red);
      take_override(v, "green", o.tolerance.green);
      take_override(v, "blue", o.tolerance.blue);
      take_override(v, "alpha", o.tolerance.alpha);
      take_override(v, "minBrightness", o.tolerance.min_brightness);
      take_override(v, "maxBrightness", o.tolerance.max_brightness);
    } else if (key == "scaleToSameSize") {
      if (v.is_boolean() && v.get<bool>()) {
        throw std::invalid_argument(
            "scaleToSameSize is not supported: it depends on the browser's resampling filter");
      }
    }
  }
}

}  // namespace aosuite::resemble

#include "renderer/technique.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>

namespace aosuite::renderer {

Technique parse_technique(std::string_view name) {
  if (name == "alchemy") return Technique::kAlchemy;
  if (name == "sao") return Technique::kSao;
  if (name == "mssao") return Technique::kMssao;
  if (name == "ue4") return Technique::kUe4;
  if (name == "pmi") return Technique::kPmi;
  throw std::invalid_argument("unknown technique '" + std::string(name) +
                              "' (expected alchemy, sao, mssao, ue4 or pmi)");
}

std::string_view technique_name(Technique t) {
  switch (t) {
    case Technique::kAlchemy:
      return "alchemy";
    case Technique::kSao:
      return "sao";
    case Technique::kMssao:
      return "mssao";
    case Technique::kUe4:
      return "ue4";
    case Technique::kPmi:
      return "pmi";
  }
  return "alchemy";
}

Blur parse_blur(std::string_view name) {
  if (name == "none") return Blur::kNone;
  if (name == "gaussian") return Blur::kGaussian;
  if (name == "bilateral") return Blur::kBilateral;
  throw std::invalid_argument("unknown blur '" + std::string(name) +
                              "' (expected none, gaussian or bilateral)");
}

std::string_view blur_name(Blur b) {
  switch (b) {
    case Blur::kNone:
      return "none";
    case Blur::kGaussian:
      return "gaussian";
    case Blur::kBilateral:
      return "bilateral";
  }
  return "none";
}

AoParams default_params(Technique t) {
  AoParams p;
  switch (t) {
    case Technique::kAlchemy:
      p.samples = 16, p.radius = 1, p.bias = 0.002f;  // beta: Unity URP's 0.002 per unit depth
      break;
    case Technique::kSao:
      p.samples = 8, p.radius = 10, p.bias = 0.012f;  // SAO::Settings bias, scene units
      break;
    case Technique::kMssao:
      p.samples = 16, p.radius = 2, p.bias = 0.002f;
      break;
    case Technique::kUe4:
      // Published Intensity 0.5 and Power 2.0; bias is a minimum horizon sine.
      p.samples = 8, p.radius = 0.05f, p.bias = 0.03f, p.intensity = 0.5f, p.contrast = 2;
      break;
    case Technique::kPmi:  // the struct's viewpoints and pmi_resolution are the paper's
      break;
  }
  return p;
}

namespace {

[[noreturn]] void bad_value(std::string_view key, std::string_view value, const char* why) {
  throw std::invalid_argument("parameter " + std::string(key) + "=" + std::string(value) + ": " +
                              why);
}

template <typename T>
T parse_number(std::string_view key, std::string_view value) {
  T out{};
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), out);
  if (ec != std::errc() || end != value.data() + value.size())
    bad_value(key, value, "not a number");
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(out)) bad_value(key, value, "not finite");
  }
  return out;
}

}  // namespace

std::array<std::string_view, 11> param_names() {
  return {"samples",    "radius",         "bias",           "intensity",
          "contrast",   "blur",           "level_weights",  "max_pixel_radius",
          "viewpoints", "pmi_resolution", "importance_best"};
}

void set_param(AoParams& p, std::string_view key, std::string_view value) {
  if (key == "samples") {
    p.samples = parse_number<int>(key, value);
  } else if (key == "radius") {
    p.radius = parse_number<float>(key, value);
  } else if (key == "bias") {
    p.bias = parse_number<float>(key, value);
  } else if (key == "intensity") {
    p.intensity = parse_number<float>(key, value);
  } else if (key == "contrast") {
    p.contrast = parse_number<float>(key, value);
  } else if (key == "max_pixel_radius") {
    p.max_pixel_radius = parse_number<float>(key, value);
  } else if (key == "viewpoints") {
    p.viewpoints = parse_number<int>(key, value);
  } else if (key == "pmi_resolution") {
    p.pmi_resolution = parse_number<int>(key, value);
  } else if (key == "importance_best") {
    p.importance_best = parse_number<int>(key, value);
  } else if (key == "blur") {
    p.blur = parse_blur(value);
  } else if (key == "level_weights") {
    std::size_t level = 0;
    for (std::string_view rest = value; level < p.level_weights.size(); ++level) {
      const std::size_t comma = rest.find(',');
      p.level_weights[level] = parse_number<float>(key, rest.substr(0, comma));
      if (comma == std::string_view::npos) {
        rest = {};
        break;
      }
      rest.remove_prefix(comma + 1);
    }
    if (level + 1 != p.level_weights.size())
      bad_value(key, value, "needs five comma-separated values");
  } else {
    std::string names;
    for (std::string_view n : param_names()) names += (names.empty() ? "" : ", ") + std::string(n);
    throw std::invalid_argument("unknown parameter '" + std::string(key) + "' (known: " + names +
                                ")");
  }
}

}  // namespace aosuite::renderer

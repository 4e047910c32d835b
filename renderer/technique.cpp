#include "renderer/technique.hpp"

#include <stdexcept>

namespace aosuite::renderer {

Technique parse_technique(std::string_view name) {
  if (name == "alchemy") return Technique::kAlchemy;
  if (name == "sao") return Technique::kSao;
  if (name == "mssao") return Technique::kMssao;
  if (name == "ue4") return Technique::kUe4;
  throw std::invalid_argument("unknown technique '" + std::string(name) +
                              "' (expected alchemy, sao, mssao or ue4)");
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
  }
  return p;
}

}  // namespace aosuite::renderer

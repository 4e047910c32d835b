// The AO techniques of the study and their parameters, with the thesis's defaults.
#pragma once

#include <array>
#include <string>
#include <string_view>

namespace aosuite::renderer {

enum class Technique { kAlchemy, kSao, kMssao, kUe4 };
Technique parse_technique(std::string_view name);  // alchemy|sao|mssao|ue4
std::string_view technique_name(Technique t);

enum class Blur { kNone, kGaussian, kBilateral };
Blur parse_blur(std::string_view name);  // none|gaussian|bilateral
std::string_view blur_name(Blur b);

struct AoParams {
  int samples = 16;
  float radius = 1;     // scene units
  float bias = 0;       // technique-specific units, see each shader's header
  float intensity = 1;  // sigma
  float contrast = 1;   // k (Alchemy), power (UE4)
  // MSSAO: intensity of each of the five levels (full, 1/2, 1/4, 1/8, 1/16); 0 skips a level
  std::array<float, 5> level_weights{1.0f, 0.5f, 0.3f, 0.3f, 0.3f};
  Blur blur = Blur::kBilateral;
};

// Thesis defaults: Alchemy r=1 s=16; SAO r=10 s=8; UE4 r=0.05 s=8; MSSAO r=2 s=16 with
// level weights 1.0/0.5/0.3/0.3/0.3. Biases and intensities are the published ones.
AoParams default_params(Technique t);

}  // namespace aosuite::renderer

// The AO techniques of the study and their parameters, with the thesis's defaults.
#pragma once

#include <array>
#include <string>
#include <string_view>

namespace aosuite::renderer {

// kPmi: viewpoint-based AO (González, Sbert & Feixas 2008), per polygon in object space
// (renderer/pmi_channel.hpp), not a screen-space estimator.
enum class Technique { kAlchemy, kSao, kMssao, kUe4, kPmi };
Technique parse_technique(std::string_view name);  // alchemy|sao|mssao|ue4|pmi
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
  // MSSAO: intensity of each of the five levels (full, 1/2, 1/4, 1/8, 1/16), times
  // `intensity`; 0 skips a level
  std::array<float, 5> level_weights{1.0f, 0.5f, 0.3f, 0.3f, 0.3f};
  // MSSAO: r_max, the most pixels a level's kernel reaches at that level's resolution
  // (Hoang & Low's cap, so each level costs the same). It is a pixel count, so at 3840x2160
  // the five levels reach half as far in the scene as at 1920x1080; 10 there matches 5 here.
  float max_pixel_radius = 5;
  Blur blur = Blur::kBilateral;
  // PMI: viewpoints on the subdivided icosahedron (12, 42, 162, 642 or 2562), the item
  // buffer's width in pixels (its height is 3/4 of it, as the paper's 640x480..2560x1920),
  // and p(V): 0 = projected area (the paper), k > 0 = the k best views (lowest VMI)
  // share 99 % of the importance and the rest share 1 % (the paper's Figure 7).
  int viewpoints = 162;
  int pmi_resolution = 1280;
  int importance_best = 0;
};

// Thesis defaults: Alchemy r=1 s=16; SAO r=10 s=8; UE4 r=0.05 s=8; MSSAO r=2 s=16 with
// level weights 1.0/0.5/0.3/0.3/0.3. Biases and intensities are the published ones. PMI: the
// paper's recommended 162 viewpoints at 1280x960 (radius, samples and bias are unused).
AoParams default_params(Technique t);

// Sets one parameter from text, as suites and `--param key=value` give them: samples, radius,
// bias, intensity, contrast, blur (none|gaussian|bilateral), level_weights ("1,0.5,0.3,0.3,0.3"),
// max_pixel_radius, viewpoints, pmi_resolution, importance_best.
// Throws std::invalid_argument naming the key and the problem (unknown key, not a number,
// non-finite, out of range).
void set_param(AoParams& params, std::string_view key, std::string_view value);
// The names set_param accepts, in a stable order.
std::array<std::string_view, 11> param_names();

}  // namespace aosuite::renderer

#include "renderer/technique.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace aosuite::renderer {

// Each screen-space technique's passes, fragment and compute, in its own file.
std::unique_ptr<AoPass> make_alchemy_pass();          // ao_pass.cpp
std::unique_ptr<AoPass> make_alchemy_compute_pass();  // ao_pass.cpp
std::unique_ptr<AoPass> make_ue4_pass();              // ao_pass.cpp
std::unique_ptr<AoPass> make_ue4_compute_pass();      // ao_pass.cpp
std::unique_ptr<AoPass> make_sao_pass();              // sao_pass.cpp
std::unique_ptr<AoPass> make_sao_compute_pass();      // sao_pass.cpp
std::unique_ptr<AoPass> make_mssao_pass();            // mssao_pass.cpp
std::unique_ptr<AoPass> make_mssao_compute_pass();    // mssao_pass.cpp
std::unique_ptr<AoPass> make_gtao_pass();             // gtao_pass.cpp
std::unique_ptr<AoPass> make_gtao_compute_pass();     // gtao_pass.cpp
std::unique_ptr<AoPass> make_bitmask_pass();          // bitmask_pass.cpp
std::unique_ptr<AoPass> make_bitmask_compute_pass();  // bitmask_pass.cpp

namespace {

// Depth fetches per pixel (TechniqueInfo::depth_taps), read off each shader's loops.
int tap_count(const AoParams& p) { return p.samples; }         // alchemy.glsl, sao.glsl
int ue4_taps(const AoParams& p) { return p.samples * 2 * 3; }  // ue4.glsl: 2 sides, kSteps 3
int slice_taps(const AoParams& p) { return p.gtao.slices * p.gtao.steps * 2; }  // per side
int no_taps(const AoParams&) { return 0; }
// Each weighted level runs Alchemy's taps over a quarter of the pixels of the level above.
int mssao_taps(const AoParams& p) {
  double taps = 0, share = 1;
  for (float w : p.mssao.level_weights) {
    if (w != 0) taps += p.samples * share;
    share /= 4;
  }
  return static_cast<int>(std::ceil(taps));
}

// The registry. Defaults are the thesis's (chapter 5) and the papers': Alchemy r=1 s=16;
// SAO r=10 s=8; UE4 r=0.05 s=8; MSSAO r=2 s=16 with level weights 1.0/0.5/0.3/0.3/0.3; PMI
// the paper's recommended 162 viewpoints at 1280x960.
constexpr TechniqueInfo kTechniques[] = {
    {Technique::kAlchemy, "alchemy", "Alchemy AO (McGuire et al. 2011)", Space::kScreen,
     Sampling::kTaps,
     [] {
       AoParams p;
       p.samples = 16, p.radius = 1, p.bias = 0.002f;  // beta: Unity URP's 0.002 per unit depth
       return p;
     },
     tap_count, make_alchemy_pass, make_alchemy_compute_pass},
    {Technique::kSao, "sao", "Scalable AO (McGuire et al. 2012)", Space::kScreen, Sampling::kTaps,
     [] {
       AoParams p;
       // SAO::Settings' bias 0.012; sao.glsl subtracts bias * radius, so this is the published
       // 0.012 scene units at r = 1 and the same share of the radius at any scene scale.
       p.samples = 8, p.radius = 10, p.bias = 0.012f;
       return p;
     },
     tap_count, make_sao_pass, make_sao_compute_pass},
    {Technique::kMssao, "mssao", "Multi-Scale AO (Hoang & Low 2012)", Space::kScreen,
     Sampling::kTaps,
     [] {
       AoParams p;
       p.samples = 16, p.radius = 2, p.bias = 0.002f;
       return p;
     },
     mssao_taps, make_mssao_pass, make_mssao_compute_pass},
    {Technique::kUe4, "ue4", "UE4 AO (Mittring 2012)", Space::kScreen, Sampling::kTaps,
     [] {
       AoParams p;
       // Published Intensity 0.5 and Power 2.0; bias is a minimum horizon sine.
       p.samples = 8, p.radius = 0.05f, p.bias = 0.03f, p.intensity = 0.5f, p.contrast = 2;
       return p;
     },
     ue4_taps, make_ue4_pass, make_ue4_compute_pass},
    {Technique::kGtao, "gtao", "Ground-Truth AO (Jimenez et al. 2016), XeGTAO's High preset",
     Space::kScreen, Sampling::kSlices,
     [] {
       AoParams p;
       // XeGTAO: radius 0.5 (times its 1.457 multiplier in the shader), FinalValuePower 2.2.
       p.radius = 0.5f, p.contrast = 2.2f;
       return p;
     },
     slice_taps, make_gtao_pass, make_gtao_compute_pass},
    {Technique::kBitmask, "bitmask",
     "visibility-bitmask AO (Therrien et al. 2023): GTAO's slices with thickness", Space::kScreen,
     Sampling::kSlices,
     [] {
       AoParams p;
       // GTAO's High preset (3 slices x 3 steps) and radius, without XeGTAO's tuned final
       // power: sectors weighted by their cosine measure already estimate the reference's AO.
       p.radius = 0.5f;
       return p;
     },
     slice_taps, make_bitmask_pass, make_bitmask_compute_pass},
    {Technique::kPmi, "pmi", "viewpoint-based AO, polygonal mutual information (Gonzalez 2008)",
     Space::kObject, Sampling::kNone, [] { return AoParams{}; }, no_taps, nullptr, nullptr},
};

}  // namespace

std::span<const TechniqueInfo> techniques() { return kTechniques; }

const TechniqueInfo& technique_info(Technique t) {
  for (const TechniqueInfo& info : kTechniques) {
    if (info.id == t) return info;
  }
  throw std::invalid_argument("unregistered technique");
}

std::vector<std::string> screen_space_technique_names() {
  std::vector<std::string> out;
  for (const TechniqueInfo& info : kTechniques)
    if (info.space == Space::kScreen) out.emplace_back(info.name);
  return out;
}

std::string technique_names(std::string_view separator) {
  std::string out;
  for (const TechniqueInfo& info : kTechniques) {
    out += (out.empty() ? "" : std::string(separator)) + std::string(info.name);
  }
  return out;
}

Technique parse_technique(std::string_view name) {
  for (const TechniqueInfo& info : kTechniques) {
    if (info.name == name) return info.id;
  }
  throw std::invalid_argument("unknown technique '" + std::string(name) + "' (expected " +
                              technique_names(", ") + ")");
}

std::string_view technique_name(Technique t) { return technique_info(t).name; }

Blur parse_blur(std::string_view name) {
  if (name == "none") return Blur::kNone;
  if (name == "gaussian") return Blur::kGaussian;
  if (name == "bilateral") return Blur::kBilateral;
  throw std::invalid_argument("unknown blur '" + std::string(name) +
                              "' (expected none, gaussian or bilateral)");
}

Pipeline parse_pipeline(std::string_view name) {
  if (name == "fragment") return Pipeline::kFragment;
  if (name == "compute") return Pipeline::kCompute;
  throw std::invalid_argument("unknown pipeline '" + std::string(name) +
                              "' (expected fragment or compute)");
}

std::string_view pipeline_name(Pipeline p) {
  return p == Pipeline::kCompute ? "compute" : "fragment";
}

GBufferKind parse_gbuffer(std::string_view name) {
  if (name == "full") return GBufferKind::kFull;
  if (name == "depth") return GBufferKind::kDepth;
  throw std::invalid_argument("unknown G-buffer '" + std::string(name) +
                              "' (expected full or depth)");
}

std::string_view gbuffer_name(GBufferKind g) { return g == GBufferKind::kDepth ? "depth" : "full"; }

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

}  // namespace aosuite::renderer

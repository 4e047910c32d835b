// A suite: the cases (scene x view x technique x parameters x resolution) the harness renders
// and checks against goldens, each with its tolerance. Read from suites/*.toml.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "compare/resemble.hpp"
#include "renderer/scene.hpp"
#include "renderer/technique.hpp"

namespace aosuite::harness {

// How far a render may stray from its golden and still pass.
struct Tolerance {
  resemble::Mode mode = resemble::Mode::kLess;  // any Resemble.js mode
  double max_mismatch_percent = 0;              // Resemble's rawMisMatchPercentage, inclusive
  int max_channel_delta = 255;                  // largest |new - golden| of any RGBA channel
  std::vector<resemble::Box> ignore;            // left, top, right, bottom, in pixels
  std::filesystem::path
      mask;  // pixels where this PNG is not black (any of R, G, B > 0) are ignored
};

// The images of a case that can be gated against goldens.
inline constexpr std::array<const char*, 3> kImageNames{"no_ao", "with_ao", "ao_only"};

struct Case {
  std::string id;  // scene-view-technique-WxH[-name]; names the golden folder
  std::shared_ptr<const renderer::Scene> scene;
  std::string scene_source;  // the built-in name or the scene file, as the suite says it
  std::string view;
  renderer::Technique technique{};
  renderer::AoParams params;
  std::map<std::string, std::string> param_overrides;  // as written in the suite, for reports
  int width = 0, height = 0;
  std::vector<std::string> images;  // which of kImageNames are gated
  Tolerance tolerance;
};

struct Suite {
  std::string name;
  std::filesystem::path file;
  // The suite's `goldens` key (relative to the suite file), else goldens/<name> relative to
  // the current directory, as reports/<name> is; `--goldens` replaces it (goldens_given).
  std::filesystem::path goldens;
  bool goldens_given = false;
  std::vector<Case> cases;
};

// Whether `name` is safe as one path component of a suite name, case id or variant tag:
// letters, digits, '-', '_', '.', not starting with '.' (so never "." or ".." nor hidden), at
// most 200 characters.
bool valid_name(std::string_view name);

// Parses and expands a suite file. Throws std::runtime_error "file:line:col: reason" for
// malformed TOML, unknown keys, wrong types, unknown scenes/views/techniques/parameters,
// impossible sizes and duplicate case ids.
Suite load_suite(const std::filesystem::path& file);

}  // namespace aosuite::harness

// A preset: one technique's parameters in a file, as `aosuite tune` will write them and as a
// person may, named wherever parameters are accepted (`render --preset`, `error --preset`, a
// suite's scene case `preset = "file.toml"`). Applied over the technique's defaults and under
// anything given beside it (--samples, --radius, --param, a case's params).
//
//   technique = "gtao"
//   [params]
//   slices = 4
//   falloff_range = 0.7
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "renderer/params.hpp"
#include "renderer/technique.hpp"

namespace aosuite::ao {

struct Preset {
  std::filesystem::path file;
  renderer::Technique technique{};
  std::vector<std::pair<std::string, std::string>> params;  // KEY, VALUE as set_param reads it
};

// Reads and checks a preset: an unknown key, technique or parameter, or a bad value, throws
// FileError naming the file, line and column.
Preset read_preset(const std::filesystem::path& file);

// Sets the preset's parameters on `params` of `technique`; throws std::invalid_argument naming
// the file when the preset is another technique's.
void apply_preset(const Preset& preset, renderer::Technique technique, renderer::AoParams& params);

}  // namespace aosuite::ao

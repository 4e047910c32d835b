// A preset: one technique's parameters in a file, as `aosuite tune` writes them and as a
// person may, named wherever parameters are accepted (`render --preset`, `error --preset`, a
// suite's scene case `preset = "..."`, a sweep grid's technique), or built in (`tuned`).
// Applied over the technique's defaults and under anything given beside it (--samples,
// --radius, --param, a case's params).
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

// A preset argument names a file when it ends in ".toml" or holds a '/'; else it names a
// built-in preset, one file per technique in ao/presets/NAME-TECHNIQUE.toml, embedded in the
// binary: `--technique gtao --preset tuned` is ao/presets/tuned-gtao.toml.
bool is_preset_file(std::string_view arg);
// The preset `arg` names for `technique`: the file (relative to `dir`) or the built-in one.
// Throws FileError for a bad file, std::invalid_argument naming the built-in presets for an
// unknown name.
Preset find_preset(const std::string& arg, renderer::Technique technique,
                   const std::filesystem::path& dir = {});
// The names of `technique`'s built-in presets ("half", "tuned"; PMI has no "half").
std::vector<std::string> builtin_preset_names(renderer::Technique technique);

// Sets the preset's parameters on `params` of `technique`; throws std::invalid_argument naming
// the file when the preset is another technique's.
void apply_preset(const Preset& preset, renderer::Technique technique, renderer::AoParams& params);

// Writes `preset` to preset.file atomically, `comment` lines first (as TOML comments): numbers
// bare, lists as arrays, words quoted, so read_preset gives the same parameters back.
void write_preset(const Preset& preset, const std::vector<std::string>& comment);

}  // namespace aosuite::ao

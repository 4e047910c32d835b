#include "ao/preset.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <map>
#include <stdexcept>

#include "common/file_io.hpp"
#include "common/toml_reader.hpp"

namespace aosuite::ao {

namespace rd = aosuite::renderer;

const std::map<std::string_view, std::string_view>& embedded_presets();  // generated

namespace {

// `source` as a preset; `file` names it in errors.
Preset parse_preset(std::string_view source, const std::filesystem::path& file) {
  toml::table root;
  try {
    root = toml::parse(source, file.string());
  } catch (const toml::parse_error& e) {
    throw FileError(fmt::format("{}:{}:{}: {}", file.string(), e.source().begin.line,
                                e.source().begin.column, e.description()));
  }
  const TomlReader r(file);  // its fail() throws FileError, "file:line:col: why"
  r.only_keys(root, {"technique", "params"});
  Preset p;
  p.file = file;
  const toml::node& technique = r.required(root, "technique");
  try {
    p.technique = rd::parse_technique(r.string(technique, "technique"));
  } catch (const std::invalid_argument& e) {
    r.fail(technique.source(), e.what());
  }
  // Each value is tried on the technique's defaults here, so a bad one is named where it is
  // written, not where the preset is used.
  rd::AoParams check = rd::default_params(p.technique);
  if (const toml::node* params = root.get("params")) {
    for (const auto& [key, value] : r.table(*params, "params")) {
      std::string text = r.param(value);
      try {
        rd::set_param(check, key.str(), text);
      } catch (const std::invalid_argument& e) {
        r.fail(value.source(), e.what());
      }
      p.params.emplace_back(std::string(key.str()), std::move(text));
    }
  }
  return p;
}

}  // namespace

Preset read_preset(const std::filesystem::path& file) {
  const std::vector<unsigned char> bytes = read_file(file);
  return parse_preset(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                      file);
}

bool is_preset_file(std::string_view arg) {
  return arg.find('/') != std::string_view::npos || arg.ends_with(".toml");
}

std::vector<std::string> builtin_preset_names(rd::Technique technique) {
  const std::string suffix = fmt::format("-{}.toml", rd::technique_name(technique));
  std::vector<std::string> names;
  for (const auto& [file, text] : embedded_presets()) {
    if (file.ends_with(suffix)) names.emplace_back(file.substr(0, file.size() - suffix.size()));
  }
  return names;
}

Preset find_preset(const std::string& arg, rd::Technique technique,
                   const std::filesystem::path& dir) {
  if (is_preset_file(arg)) return read_preset(dir / arg);
  const std::string file = fmt::format("{}-{}.toml", arg, rd::technique_name(technique));
  const auto& embedded = embedded_presets();
  const auto it = embedded.find(file);
  if (it == embedded.end()) {
    throw std::invalid_argument(fmt::format(
        "no built-in preset '{}' for {} (its built-in ones: {}; a preset file ends "
        "in .toml)",
        arg, rd::technique_name(technique), fmt::join(builtin_preset_names(technique), ", ")));
  }
  return parse_preset(it->second, "built-in preset " + file);
}

void apply_preset(const Preset& preset, rd::Technique technique, rd::AoParams& params) {
  if (preset.technique != technique) {
    throw std::invalid_argument(fmt::format("{}: a preset for {}, not {}", preset.file.string(),
                                            rd::technique_name(preset.technique),
                                            rd::technique_name(technique)));
  }
  for (const auto& [key, value] : preset.params) rd::set_param(params, key, value);
}

namespace {

// A value as set_param reads it, as TOML: "1,0.5" -> [1, 0.5]; "bilateral" -> "bilateral".
std::string toml_value(const std::string& text) {
  if (text.find(',') != std::string::npos) {
    std::string out = "[";
    for (char c : text) out += c == ',' ? std::string(", ") : std::string(1, c);
    return out + "]";
  }
  double number = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
  if (ec == std::errc() && end == text.data() + text.size()) return text;
  return "\"" + text + "\"";  // a word set_param took (a blur's name): nothing to escape
}

}  // namespace

void write_preset(const Preset& preset, const std::vector<std::string>& comment) {
  std::string out;
  for (const std::string& line : comment) out += "# " + line + "\n";
  out += fmt::format("technique = \"{}\"\n\n[params]\n", rd::technique_name(preset.technique));
  for (const auto& [key, value] : preset.params) out += key + " = " + toml_value(value) + "\n";
  if (preset.file.has_parent_path()) std::filesystem::create_directories(preset.file.parent_path());
  write_text(preset.file, out);
}

}  // namespace aosuite::ao

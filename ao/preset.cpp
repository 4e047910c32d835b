#include "ao/preset.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <stdexcept>

#include "common/file_io.hpp"
#include "common/toml_reader.hpp"

namespace aosuite::ao {

namespace rd = aosuite::renderer;

Preset read_preset(const std::filesystem::path& file) {
  const std::vector<unsigned char> bytes = read_file(file);
  toml::table root;
  try {
    root = toml::parse(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                       file.string());
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

void apply_preset(const Preset& preset, rd::Technique technique, rd::AoParams& params) {
  if (preset.technique != technique) {
    throw std::invalid_argument(fmt::format("{}: a preset for {}, not {}", preset.file.string(),
                                            rd::technique_name(preset.technique),
                                            rd::technique_name(technique)));
  }
  for (const auto& [key, value] : preset.params) rd::set_param(params, key, value);
}

}  // namespace aosuite::ao

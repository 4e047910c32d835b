#include "ao/sweep_grid.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include "ao/preset.hpp"
#include "common/toml_reader.hpp"
#include "image/image_io.hpp"
#include "renderer/params.hpp"

namespace aosuite::ao {
namespace {

namespace fs = std::filesystem;

template <typename T>
std::vector<T> numbers(const toml::node_view<const toml::node>& node, const std::string& where) {
  std::vector<T> out;
  const toml::array* arr = node.as_array();
  if (!arr || arr->empty()) throw std::invalid_argument(where + " must be a non-empty array");
  for (const toml::node& n : *arr) {
    const std::optional<double> v = n.value<double>();
    if (!v) throw std::invalid_argument(where + " must hold numbers");
    out.push_back(static_cast<T>(*v));
  }
  return out;
}

std::vector<std::string> strings(const toml::node_view<const toml::node>& node,
                                 const std::string& where) {
  std::vector<std::string> out;
  if (!node) return out;
  const toml::array* arr = node.as_array();
  if (!arr) throw std::invalid_argument(where + " must be an array of strings");
  for (const toml::node& n : *arr) {
    const std::optional<std::string> v = n.value<std::string>();
    if (!v) throw std::invalid_argument(where + " must hold strings");
    out.push_back(*v);
  }
  return out;
}

// A technique's fixed parameters, each checked against the technique's defaults now so a
// bad key or value fails before anything renders.
std::map<std::string, std::string> fixed_params(const toml::node_view<const toml::node>& node,
                                                renderer::Technique technique, const fs::path& path,
                                                const std::string& where) {
  const toml::table* table = node.as_table();
  if (!table) throw std::invalid_argument(where + " must be a table, e.g. { blur = \"none\" }");
  const TomlReader reader(path);
  std::map<std::string, std::string> out;
  for (const auto& [key, value] : *table) {
    const std::string k(key.str());
    if (k == "samples" || k == "radius" || k == "intensity") {
      throw std::invalid_argument(fmt::format("{}.{}: {} is one of the grid's axes", where, k, k));
    }
    const std::string text = reader.param(value);
    renderer::AoParams probe = renderer::default_params(technique);
    try {
      renderer::set_param(probe, k, text);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("{}.{}: {}", where, k, e.what()));
    }
    out[k] = text;
  }
  return out;
}

// A preset file (relative to the grid) or built-in name: its values under the table's params,
// and its sample count and intensity where the grid gives no such axis (its radius never: the
// radius is the study's axis).
void add_preset(TechniqueGrid& tg, const std::string& name, const fs::path& path) {
  const Preset preset = find_preset(name, tg.technique, path.parent_path());
  renderer::AoParams probe = renderer::default_params(tg.technique);
  apply_preset(preset, tg.technique, probe);  // throws for another technique's preset
  for (const auto& [k, v] : preset.params) {
    if (k == "samples") {
      if (tg.samples.empty()) tg.samples = {probe.samples};
    } else if (k == "intensity") {
      if (tg.intensities.empty()) tg.intensities = {probe.intensity};
    } else if (k != "radius") {
      tg.params.emplace(k, v);  // the table's own params win
    }
  }
}

SweepGrid parse(const toml::table& t, const fs::path& path, const std::string& preset) {
  SweepGrid g;
  g.name = t["name"].value_or(path.stem().string());
  for (std::string s : strings(t["scenes"], "scenes")) {
    // Scene files are relative to the grid file; built-in names stay as they are.
    if (s.ends_with(".toml") && fs::path(s).is_relative()) s = (path.parent_path() / s).string();
    g.scenes.push_back(s);
  }
  if (g.scenes.empty()) throw std::invalid_argument("scenes must name at least one scene");
  g.views = strings(t["views"], "views");
  const toml::array* res = t["resolutions"].as_array();
  if (!res || res->empty()) throw std::invalid_argument("resolutions must be [[w, h], ...]");
  for (const toml::node& r : *res) {
    const std::vector<int> wh = numbers<int>(toml::node_view<const toml::node>(r), "resolutions");
    if (wh.size() != 2 || wh[0] < 16 || wh[1] < 16 || wh[0] > 8192 || wh[1] > 8192)
      throw std::invalid_argument("each resolution must be [w, h] with sides 16..8192");
    g.resolutions.emplace_back(wh[0], wh[1]);
  }
  g.runs = t["runs"].value_or(g.runs);
  g.rays = t["rays"].value_or(g.rays);
  g.unbounded = t["unbounded"].value_or(g.unbounded);
  if (g.runs < 1 || g.runs > 100) throw std::invalid_argument("runs must be 1..100");
  if (g.rays < 1 || g.rays > 65536) throw std::invalid_argument("rays must be 1..65536");
  const toml::table* techniques = t["techniques"].as_table();
  if (!techniques || techniques->empty())
    throw std::invalid_argument("[techniques.NAME] tables are missing");
  for (const auto& [name, node] : *techniques) {
    const std::string where = fmt::format("techniques.{}", name.str());
    const auto tv = toml::node_view<const toml::node>(node);
    const renderer::Technique technique = renderer::parse_technique(name.str());
    // A technique that takes no sample count (GTAO: slices and steps) has no samples axis.
    const bool takes_samples = renderer::applies(renderer::param_spec("samples"), technique);
    if (!takes_samples && tv["samples"]) {
      throw std::invalid_argument(fmt::format(
          "{}.samples: {} takes no sample count (set its own keys in params)", where, name.str()));
    }
    TechniqueGrid tg{technique,
                     // A preset may give the sample count (add_preset).
                     !takes_samples ? std::vector<int>{0}
                     : (tv["preset"] || !preset.empty()) && !tv["samples"]
                         ? std::vector<int>{}
                         : numbers<int>(tv["samples"], where + ".samples"),
                     numbers<float>(tv["radius"], where + ".radius"),
                     {},
                     {}};
    if (tv["intensity"]) tg.intensities = numbers<float>(tv["intensity"], where + ".intensity");
    if (tv["params"]) tg.params = fixed_params(tv["params"], tg.technique, path, where + ".params");
    if (tv["preset"]) {
      const std::optional<std::string> own = tv["preset"].value<std::string>();
      if (!own) throw std::invalid_argument(where + ".preset must be a string");
      add_preset(tg, *own, path);
    } else if (!preset.empty()) {
      add_preset(tg, preset, path);
    }
    if (tg.samples.empty()) tg.samples = {renderer::default_params(technique).samples};
    g.techniques.push_back(std::move(tg));
  }
  return g;
}

}  // namespace

SweepGrid read_sweep_grid(const fs::path& path, const std::string& preset) {
  const std::vector<unsigned char> bytes = read_file(path);
  try {
    const toml::table t = toml::parse(
        std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path.string());
    return parse(t, path, preset);
  } catch (const toml::parse_error& e) {
    throw FileError(fmt::format("{}:{}:{}: {}", path.string(), e.source().begin.line,
                                e.source().begin.column, e.description()));
  } catch (const std::invalid_argument& e) {
    throw FileError(fmt::format("{}: {}", path.string(), e.what()));
  }
}

}  // namespace aosuite::ao

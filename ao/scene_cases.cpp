#include "ao/scene_cases.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <span>

#include "ao/ao_effect_report.hpp"
#include "ao/preset.hpp"
#include "ao/scene_maker.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::ao {
namespace {

namespace rd = aosuite::renderer;
using harness::Case;

// `key` from the case's table, else from [defaults], else null.
const toml::node* own_or_default(const harness::CaseTable& t, std::string_view key) {
  if (const toml::node* n = t.table.get(key)) return n;
  return t.defaults ? t.defaults->get(key) : nullptr;
}

std::vector<std::string> read_techniques(const harness::CaseTable& t) {
  const toml::node* n = own_or_default(t, "techniques");
  if (!n) return rd::screen_space_technique_names();
  std::vector<std::string> names = t.reader.strings(*n, "techniques");
  for (const std::string& name : names) {
    try {
      rd::parse_technique(name);
    } catch (const std::invalid_argument& e) {
      t.reader.fail(n->source(), e.what());
    }
  }
  return names;
}

std::vector<std::string> read_images(const harness::CaseTable& t) {
  const toml::node* n = own_or_default(t, "images");
  if (!n) return {"with_ao"};
  std::vector<std::string> names = t.reader.strings(*n, "images");
  for (const std::string& name : names) {
    if (std::ranges::find(kImageNames, name) == kImageNames.end()) {
      t.reader.fail(n->source(),
                    "unknown image '" + name + "' (no_ao, with_ao, ao_only, ao_float)");
    }
  }
  return names;
}

// The scene a case names, read once per suite however many cases name it.
std::shared_ptr<const rd::Scene> scene_of(const harness::CaseTable& t, const toml::node& at,
                                          const std::string& source) {
  std::shared_ptr<const void>& kept = t.memo["scene:" + source];
  if (!kept) {
    try {
      const bool is_file = source.ends_with(".toml");
      kept = std::make_shared<const rd::Scene>(
          rd::load_scene(is_file ? (t.dir / source).string() : source));
    } catch (const std::exception& e) {
      t.reader.fail(at.source(), e.what());
    }
  }
  return std::static_pointer_cast<const rd::Scene>(kept);
}

struct SceneCaseKind final : harness::CaseKind {
  std::string_view name() const override { return "render"; }
  std::string_view key() const override { return "scene"; }
  std::vector<std::string_view> case_keys() const override {
    return {"views", "techniques", "images", "allow_empty", "preset"};
  }
  std::vector<std::string_view> default_keys() const override { return {"techniques", "images"}; }

  void expand(const harness::CaseTable& t, std::vector<Case>& out) const override {
    const TomlReader& r = t.reader;
    const toml::node& scene_node = *t.table.get("scene");
    const std::string source = r.string(scene_node, "scene");
    const std::shared_ptr<const rd::Scene> scene = scene_of(t, scene_node, source);
    const std::vector<std::string> techniques = read_techniques(t);
    const std::vector<std::string> images = read_images(t);
    const toml::node* allow_empty = t.table.get("allow_empty");
    // A preset file relative to the suite, or a built-in preset's name (ao/preset.hpp): over
    // the technique's defaults, under the case's params.
    const toml::node* preset_node = t.table.get("preset");
    const std::string preset = preset_node ? r.string(*preset_node, "preset") : std::string();
    std::vector<std::string> views;
    if (const toml::node* n = t.table.get("views")) {
      views = r.strings(*n, "views");
      for (const std::string& v : views) {
        try {
          rd::find_view(*scene, v);
        } catch (const std::invalid_argument& e) {
          r.fail(n->source(), e.what());
        }
      }
    } else {
      for (const rd::View& v : scene->views) views.push_back(v.name);
    }
    if (std::ranges::count(images, "ao_float") && t.base.tolerance.gates_for(true).empty()) {
      r.fail(t.table.source(),
             "ao_float is judged by metric gates only: give the tolerance one "
             "(e.g. rmse = { max = 0.01 })");
    }
    for (const std::string& view : views) {
      for (const std::string& technique : techniques) {
        auto made = std::make_shared<SceneCase>();
        made->scene = scene;
        made->view = rd::find_view(*scene, view).name;
        made->technique = rd::parse_technique(technique);
        made->params = rd::default_params(made->technique);
        made->allow_empty = allow_empty && r.boolean(*allow_empty, "allow_empty");
        if (preset_node) {
          try {
            apply_preset(find_preset(preset, made->technique, t.dir), made->technique,
                         made->params);
          } catch (const std::exception& e) {
            r.fail(preset_node->source(), e.what());
          }
        }
        for (const auto& [key, value] : t.base.param_overrides) {
          try {
            rd::set_param(made->params, key, value);
          } catch (const std::invalid_argument& e) {
            r.fail(t.param_at.at(key), e.what());
          }
        }
        Case k = t.base;
        k.images = images;
        k.id = fmt::format("{}-{}-{}-{}x{}{}", scene->name, made->view, technique, k.width,
                           k.height, t.suffix);
        k.made = std::move(made);
        out.push_back(std::move(k));
      }
    }
  }

  std::unique_ptr<harness::Maker> maker(harness::Environment* env) const override {
    return make_scene_maker(env);
  }

  std::string report_section(const harness::RunResults& run,
                             const std::filesystem::path& report_dir) const override {
    return ao_effect_section(run, report_dir);
  }
};

}  // namespace

void register_scene_cases() { harness::register_kind(std::make_unique<SceneCaseKind>()); }

}  // namespace aosuite::ao

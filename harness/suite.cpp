#include "harness/suite.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <set>
#include <stdexcept>

#include "harness/escape.hpp"
#include "renderer/params.hpp"
#include "renderer/scene_file.hpp"
#include "renderer/toml_reader.hpp"

namespace aosuite::harness {
namespace {

namespace fs = std::filesystem;

using Reader = TomlReader;

void read_params(const Reader& r, const toml::node& n, std::map<std::string, std::string>& out,
                 std::map<std::string, toml::source_region>& where) {
  for (const auto& [key, value] : r.table(n, "params")) {
    out[std::string(key.str())] = r.param(value);
    where[std::string(key.str())] = value.source();
  }
}

void read_tolerance(const Reader& r, const fs::path& dir, const toml::node& n, Tolerance& t) {
  const toml::table& tbl = r.table(n, "tolerance");
  r.only_keys(tbl, {"mode", "max_mismatch_percent", "max_channel_delta", "ignore", "mask"});
  if (const toml::node* m = tbl.get("mode")) {
    try {
      t.mode = resemble::parse_mode(r.string(*m, "mode"));
    } catch (const std::invalid_argument& e) {
      r.fail(m->source(), e.what());
    }
  }
  if (const toml::node* m = tbl.get("max_mismatch_percent")) {
    t.max_mismatch_percent = r.number(*m, "max_mismatch_percent");
    if (!(t.max_mismatch_percent >= 0 && t.max_mismatch_percent <= 100)) {
      r.fail(m->source(), "max_mismatch_percent must be 0..100");
    }
  }
  if (const toml::node* m = tbl.get("max_channel_delta")) {
    t.max_channel_delta = r.integer(*m, "max_channel_delta", 0, 255);
  }
  if (const toml::node* m = tbl.get("ignore")) {
    t.ignore.clear();
    const toml::array* boxes = m->as_array();
    if (!boxes) r.fail(m->source(), "ignore must be an array of [left, top, right, bottom]");
    for (const toml::node& b : *boxes) {
      const toml::array* box = b.as_array();
      if (!box || box->size() != 4) r.fail(b.source(), "a box is [left, top, right, bottom]");
      resemble::Box out;
      out.left = r.integer((*box)[0], "left", 0, 1 << 20);
      out.top = r.integer((*box)[1], "top", 0, 1 << 20);
      out.right = r.integer((*box)[2], "right", 0, 1 << 20);
      out.bottom = r.integer((*box)[3], "bottom", 0, 1 << 20);
      if (out.right < out.left || out.bottom < out.top)
        r.fail(b.source(), "box has right < left or bottom < top");
      t.ignore.push_back(out);
    }
  }
  if (const toml::node* m = tbl.get("mask")) {
    t.mask = dir / r.string(*m, "mask");
    if (!fs::is_regular_file(t.mask)) r.fail(m->source(), "no mask image " + t.mask.string());
  }
}

// What [defaults] and a [[case]] may both say.
struct Common {
  int width = 320, height = 180;
  std::vector<std::string> techniques{"alchemy", "sao", "mssao", "ue4"};
  std::vector<std::string> images{"with_ao"};
  std::map<std::string, std::string> params;
  std::map<std::string, toml::source_region> param_at;
  Tolerance tolerance;
};

void read_common(const Reader& r, const fs::path& dir, const toml::table& t, Common& c) {
  if (const toml::node* n = t.get("width")) c.width = r.integer(*n, "width", 1, 16384);
  if (const toml::node* n = t.get("height")) c.height = r.integer(*n, "height", 1, 16384);
  if (const toml::node* n = t.get("techniques")) {
    c.techniques = r.strings(*n, "techniques");
    for (const std::string& name : c.techniques) {
      try {
        renderer::parse_technique(name);
      } catch (const std::invalid_argument& e) {
        r.fail(n->source(), e.what());
      }
    }
  }
  if (const toml::node* n = t.get("images")) {
    c.images = r.strings(*n, "images");
    for (const std::string& name : c.images) {
      if (std::find(kImageNames.begin(), kImageNames.end(), name) == kImageNames.end()) {
        r.fail(n->source(), "unknown image '" + name + "' (no_ao, with_ao, ao_only)");
      }
    }
  }
  if (const toml::node* n = t.get("params")) read_params(r, *n, c.params, c.param_at);
  if (const toml::node* n = t.get("tolerance")) read_tolerance(r, dir, *n, c.tolerance);
}

}  // namespace

bool valid_name(std::string_view id) {
  return !id.empty() && id.size() <= 200 && id.front() != '.' &&
         std::all_of(id.begin(), id.end(), [](char ch) {
           return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                  (ch >= '0' && ch <= '9') || ch == '-' || ch == '_' || ch == '.';
         });
}

Suite load_suite(const fs::path& file) {
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    const auto& at = e.source().begin;
    throw std::runtime_error(
        fmt::format("{}:{}:{}: {}", file.string(), at.line, at.column, e.description()));
  }
  const Reader r(file);
  const fs::path dir = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  r.only_keys(root, {"name", "goldens", "defaults", "case"});

  Suite suite;
  suite.file = file;
  suite.name = file.stem().string();
  if (const toml::node* n = root.get("name")) suite.name = r.string(*n, "name");
  if (!valid_name(suite.name)) {
    r.fail(root.get("name") ? root.get("name")->source() : root.source(),
           "suite name '" + printable(suite.name) +
               "' must be letters, digits, - _ . and not start with '.' (it names folders)");
  }
  suite.goldens = fs::path("goldens") / suite.name;
  if (const toml::node* n = root.get("goldens")) suite.goldens = dir / r.string(*n, "goldens");
  suite.goldens = suite.goldens.lexically_normal();

  Common defaults;
  if (const toml::node* n = root.get("defaults")) {
    const toml::table& t = r.table(*n, "defaults");
    r.only_keys(t, {"width", "height", "techniques", "images", "params", "tolerance"});
    read_common(r, dir, t, defaults);
  }
  const toml::array* cases = root.get_as<toml::array>("case");
  if (!cases || cases->empty()) r.fail(root.source(), "a suite needs at least one [[case]]");

  std::map<std::string, std::shared_ptr<const renderer::Scene>> scenes;
  std::set<std::string> ids;
  for (const toml::node& node : *cases) {
    const toml::table& t = r.table(node, "case");
    r.only_keys(t, {"scene", "views", "name", "width", "height", "techniques", "images", "params",
                    "tolerance"});
    const toml::node* scene_node = t.get("scene");
    if (!scene_node) r.fail(t.source(), "a case needs scene = \"<built-in name or file.toml>\"");
    const std::string source = r.string(*scene_node, "scene");
    auto& scene = scenes[source];
    if (!scene) {
      try {
        const bool is_file = source.ends_with(".toml");
        scene = std::make_shared<const renderer::Scene>(
            renderer::load_scene(is_file ? (dir / source).string() : source));
      } catch (const std::exception& e) {
        r.fail(scene_node->source(), e.what());
      }
    }
    Common c = defaults;
    read_common(r, dir, t, c);
    std::vector<std::string> views;
    if (const toml::node* n = t.get("views")) {
      views = r.strings(*n, "views");
      for (const std::string& v : views) {
        try {
          renderer::find_view(*scene, v);
        } catch (const std::invalid_argument& e) {
          r.fail(n->source(), e.what());
        }
      }
    } else {
      for (const renderer::View& v : scene->views) views.push_back(v.name);
    }
    std::string suffix;
    if (const toml::node* n = t.get("name")) suffix = "-" + r.string(*n, "name");

    for (const std::string& view : views) {
      for (const std::string& technique : c.techniques) {
        Case k;
        k.scene = scene;
        k.scene_source = source;
        k.view = renderer::find_view(*scene, view).name;
        k.technique = renderer::parse_technique(technique);
        k.params = renderer::default_params(k.technique);
        for (const auto& [key, value] : c.params) {
          try {
            renderer::set_param(k.params, key, value);
          } catch (const std::invalid_argument& e) {
            r.fail(c.param_at.at(key), e.what());
          }
        }
        k.param_overrides = c.params;
        k.width = c.width, k.height = c.height;
        k.images = c.images;
        k.tolerance = c.tolerance;
        k.id = fmt::format("{}-{}-{}-{}x{}{}", scene->name, k.view, technique, k.width, k.height,
                           suffix);
        if (!valid_name(k.id)) {
          r.fail(t.source(), "case id '" + k.id +
                                 "' may hold only letters, digits, - _ . and not start with '.'");
        }
        if (!ids.insert(k.id).second) r.fail(t.source(), "duplicate case '" + k.id + "'");
        suite.cases.push_back(std::move(k));
      }
    }
  }
  return suite;
}

}  // namespace aosuite::harness

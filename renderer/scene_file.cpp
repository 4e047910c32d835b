#include "renderer/scene_file.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "compare/image_io.hpp"
#include "renderer/mesh_io.hpp"

namespace aosuite::renderer {
namespace {

namespace fs = std::filesystem;

// Typed access to a parsed scene file; every error names the file, line and column.
class SceneReader {
 public:
  explicit SceneReader(fs::path file) : file_(std::move(file)) {}
  const fs::path& file() const { return file_; }

  [[noreturn]] void fail(const toml::source_region& at, std::string_view why) const {
    throw FileError(
        fmt::format("{}:{}:{}: {}", file_.string(), at.begin.line, at.begin.column, why));
  }

  void allow_only(const toml::table& t, std::initializer_list<std::string_view> keys) const {
    for (const auto& [key, value] : t) {
      if (std::find(keys.begin(), keys.end(), key.str()) != keys.end()) continue;
      std::string known;
      for (std::string_view k : keys) known += (known.empty() ? "" : ", ") + std::string(k);
      fail(key.source(), fmt::format("unknown key '{}' (allowed: {})", key.str(), known));
    }
  }

  const toml::node& required(const toml::table& t, std::string_view key) const {
    if (const toml::node* n = t.get(key)) return *n;
    fail(t.source(), fmt::format("missing '{}'", key));
  }

  // A finite number (integer or float); TOML's nan and inf are refused.
  float number(const toml::node& n, std::string_view what) const {
    std::optional<double> v = n.value_exact<double>();
    if (const auto i = n.value_exact<std::int64_t>()) v = static_cast<double>(*i);
    if (!v) fail(n.source(), fmt::format("{} must be a number", what));
    const auto f = static_cast<float>(*v);
    if (!std::isfinite(f)) fail(n.source(), fmt::format("{} must be finite", what));
    return f;
  }
  float positive(const toml::node& n, std::string_view what) const {
    const float v = number(n, what);
    if (!(v > 0)) fail(n.source(), fmt::format("{} must be positive", what));
    return v;
  }

  glm::vec3 vec3(const toml::node& n, std::string_view what) const {
    const toml::array* a = n.as_array();
    if (!a || a->size() != 3)
      fail(n.source(), fmt::format("{} must be an array of 3 numbers", what));
    return {number((*a)[0], what), number((*a)[1], what), number((*a)[2], what)};
  }

  const toml::table& table(const toml::node& n, std::string_view what) const {
    if (const toml::table* t = n.as_table()) return *t;
    fail(n.source(), fmt::format("{} must be a table", what));
  }

  // An array of tables, at least one.
  std::vector<const toml::table*> tables(const toml::node& n, std::string_view what) const {
    const toml::array* a = n.as_array();
    if (!a) fail(n.source(), fmt::format("{} must be an array of tables ([[{}]])", what, what));
    std::vector<const toml::table*> out;
    for (const toml::node& e : *a) out.push_back(&table(e, what));
    if (out.empty()) fail(n.source(), fmt::format("{} must not be empty", what));
    return out;
  }

  // A name that is safe as part of an output file name.
  std::string name(const toml::node& n, std::string_view what) const {
    const std::optional<std::string> s = n.value_exact<std::string>();
    if (!s) fail(n.source(), fmt::format("{} must be a string", what));
    const bool safe =
        !s->empty() && s->front() != '.' && std::all_of(s->begin(), s->end(), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
        });
    if (!safe) fail(n.source(), fmt::format("{} '{}' must be letters, digits, _ - .", what, *s));
    return *s;
  }

 private:
  fs::path file_;
};

// The geometry of one [[meshes]] entry: a file or exactly one built-in primitive.
Mesh mesh_geometry(const SceneReader& r, const toml::table& t) {
  const char* kinds[] = {"file", "box", "sphere", "quad", "plane"};
  const auto given = std::count_if(std::begin(kinds), std::end(kinds),
                                   [&](const char* k) { return t.contains(k); });
  if (given != 1) {
    r.fail(t.source(), "a mesh needs exactly one of file, box, sphere, quad, plane");
  }
  const glm::vec3 colour(0.8f);
  if (const toml::node* n = t.get("file")) {
    const std::optional<std::string> file = n->value_exact<std::string>();
    if (!file) r.fail(n->source(), "file must be a string");
    try {
      return load_mesh(r.file().parent_path() / *file);
    } catch (const std::exception& e) {
      r.fail(n->source(), e.what());
    }
  }
  if (const toml::node* n = t.get("box")) {
    const toml::table& b = r.table(*n, "box");
    r.allow_only(b, {"min", "max"});
    const glm::vec3 lo = r.vec3(r.required(b, "min"), "box.min");
    const glm::vec3 hi = r.vec3(r.required(b, "max"), "box.max");
    if (!glm::all(glm::lessThan(lo, hi))) r.fail(n->source(), "box.min must be below box.max");
    return make_box(lo, hi, colour);
  }
  if (const toml::node* n = t.get("sphere")) {
    const toml::table& s = r.table(*n, "sphere");
    r.allow_only(s, {"centre", "radius", "segments"});
    int segments = 48;
    if (const toml::node* seg = s.get("segments")) {
      const std::optional<std::int64_t> v = seg->value_exact<std::int64_t>();
      if (!v || *v < 4 || *v > 1024) r.fail(seg->source(), "segments must be an integer 4..1024");
      segments = static_cast<int>(*v);
    }
    return make_sphere(r.vec3(r.required(s, "centre"), "sphere.centre"),
                       r.positive(r.required(s, "radius"), "sphere.radius"), segments, colour);
  }
  if (const toml::node* n = t.get("quad")) {
    const toml::table& q = r.table(*n, "quad");
    r.allow_only(q, {"corner", "edge_u", "edge_v"});
    return make_quad(r.vec3(r.required(q, "corner"), "quad.corner"),
                     r.vec3(r.required(q, "edge_u"), "quad.edge_u"),
                     r.vec3(r.required(q, "edge_v"), "quad.edge_v"), colour);
  }
  // A square ground of side `plane` at y = 0, facing up, centred on the origin.
  const float h = 0.5f * r.positive(*t.get("plane"), "plane");
  return make_quad({-h, 0, -h}, {0, 0, 2 * h}, {2 * h, 0, 0}, colour);
}

Mesh read_mesh(const SceneReader& r, const toml::table& t) {
  r.allow_only(t, {"file", "box", "sphere", "quad", "plane", "fit", "scale", "rotate_degrees",
                   "on_ground", "translate", "colour"});
  Mesh mesh = mesh_geometry(r, t);
  Placement p;
  if (const toml::node* n = t.get("fit")) p.fit = r.positive(*n, "fit");
  if (const toml::node* n = t.get("scale")) {
    p.scale = n->is_array() ? r.vec3(*n, "scale") : glm::vec3(r.number(*n, "scale"));
    if (!glm::all(glm::greaterThan(p.scale, glm::vec3(0)))) {
      r.fail(n->source(), "scale must be positive");
    }
  }
  if (const toml::node* n = t.get("rotate_degrees"))
    p.rotate_degrees = r.vec3(*n, "rotate_degrees");
  if (const toml::node* n = t.get("on_ground")) {
    const std::optional<bool> b = n->value_exact<bool>();
    if (!b) r.fail(n->source(), "on_ground must be true or false");
    p.on_ground = *b;
  }
  if (const toml::node* n = t.get("translate")) p.translate = r.vec3(*n, "translate");
  try {
    place_mesh(mesh, p);
  } catch (const std::invalid_argument& e) {
    r.fail(t.source(), e.what());
  }
  if (const toml::node* n = t.get("colour")) {
    mesh.colour = r.vec3(*n, "colour");
    if (!glm::all(glm::greaterThanEqual(mesh.colour, glm::vec3(0))) ||
        !glm::all(glm::lessThanEqual(mesh.colour, glm::vec3(1)))) {
      r.fail(n->source(), "colour components must be in 0..1");
    }
  }
  return mesh;
}

View read_view(const SceneReader& r, const toml::table& t) {
  r.allow_only(t, {"name", "eye", "target", "up", "fovy_degrees", "near"});
  View v;
  v.name = r.name(r.required(t, "name"), "view name");
  v.eye = r.vec3(r.required(t, "eye"), "eye");
  v.target = r.vec3(r.required(t, "target"), "target");
  if (const toml::node* n = t.get("up")) v.up = r.vec3(*n, "up");
  if (const toml::node* n = t.get("fovy_degrees")) {
    v.fovy_degrees = r.number(*n, "fovy_degrees");
    if (!(v.fovy_degrees > 0 && v.fovy_degrees < 180)) {
      r.fail(n->source(), "fovy_degrees must be in (0, 180)");
    }
  }
  if (const toml::node* n = t.get("near")) v.near = r.positive(*n, "near");
  // A camera needs a direction and an up that is not along it, else its basis is NaN.
  const glm::vec3 forward = v.target - v.eye;
  const float dir = glm::length(forward), side = glm::length(glm::cross(forward, v.up));
  if (!(dir > 0 && std::isfinite(dir))) r.fail(t.source(), "eye and target must differ");
  if (!(side > 1e-6f * dir * glm::length(v.up))) {
    r.fail(t.source(), "up must not be parallel to the view direction");
  }
  return v;
}

}  // namespace

Scene load_scene_file(const fs::path& path) {
  const std::vector<unsigned char> bytes = read_file(path);
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const SceneReader r(path);
  toml::table root;
  try {
    root = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    r.fail(e.source(), e.description());
  }
  r.allow_only(root, {"name", "meshes", "views"});
  Scene scene;
  scene.name = root.contains("name") ? r.name(*root.get("name"), "name") : path.stem().string();
  for (const toml::table* t : r.tables(r.required(root, "meshes"), "meshes")) {
    scene.meshes.push_back(read_mesh(r, *t));
  }
  std::set<std::string> names;
  for (const toml::table* t : r.tables(r.required(root, "views"), "views")) {
    scene.views.push_back(read_view(r, *t));
    if (!names.insert(scene.views.back().name).second) {
      r.fail(t->source(), fmt::format("duplicate view name '{}'", scene.views.back().name));
    }
  }
  return scene;
}

Scene load_scene(std::string_view name_or_path) {
  if (name_or_path.ends_with(".toml")) return load_scene_file(name_or_path);
  return builtin_scene(name_or_path);
}

}  // namespace aosuite::renderer

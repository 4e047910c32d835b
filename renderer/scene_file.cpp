#include "renderer/scene_file.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "compare/image_io.hpp"
#include "renderer/mesh_io.hpp"
#include "renderer/toml_reader.hpp"

namespace aosuite::renderer {
namespace {

namespace fs = std::filesystem;

using SceneReader = TomlReader;

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
    const std::string file = r.string(*n, "file");
    try {
      return load_mesh(r.file().parent_path() / file);
    } catch (const std::exception& e) {
      r.fail(n->source(), e.what());
    }
  }
  if (const toml::node* n = t.get("box")) {
    const toml::table& b = r.table(*n, "box");
    r.only_keys(b, {"min", "max"});
    const glm::vec3 lo = r.vec3(r.required(b, "min"), "box.min");
    const glm::vec3 hi = r.vec3(r.required(b, "max"), "box.max");
    if (!glm::all(glm::lessThan(lo, hi))) r.fail(n->source(), "box.min must be below box.max");
    return make_box(lo, hi, colour);
  }
  if (const toml::node* n = t.get("sphere")) {
    const toml::table& s = r.table(*n, "sphere");
    r.only_keys(s, {"centre", "radius", "segments"});
    int segments = 48;
    if (const toml::node* seg = s.get("segments")) segments = r.integer(*seg, "segments", 4, 1024);
    return make_sphere(r.vec3(r.required(s, "centre"), "sphere.centre"),
                       static_cast<float>(r.positive(r.required(s, "radius"), "sphere.radius")),
                       segments, colour);
  }
  if (const toml::node* n = t.get("quad")) {
    const toml::table& q = r.table(*n, "quad");
    r.only_keys(q, {"corner", "edge_u", "edge_v"});
    return make_quad(r.vec3(r.required(q, "corner"), "quad.corner"),
                     r.vec3(r.required(q, "edge_u"), "quad.edge_u"),
                     r.vec3(r.required(q, "edge_v"), "quad.edge_v"), colour);
  }
  // A square ground of side `plane` at y = 0, facing up, centred on the origin.
  const auto h = static_cast<float>(0.5 * r.positive(*t.get("plane"), "plane"));
  Mesh m = make_quad({-h, 0, -h}, {0, 0, 2 * h}, {2 * h, 0, 0}, colour);
  m.ground = true;
  return m;
}

Mesh read_mesh(const SceneReader& r, const toml::table& t) {
  r.only_keys(t, {"file", "box", "sphere", "quad", "plane", "fit", "scale", "rotate_degrees",
                  "on_ground", "translate", "colour"});
  Mesh mesh = mesh_geometry(r, t);
  Placement p;
  if (const toml::node* n = t.get("fit")) p.fit = static_cast<float>(r.positive(*n, "fit"));
  if (const toml::node* n = t.get("scale")) {
    p.scale =
        n->is_array() ? r.vec3(*n, "scale") : glm::vec3(static_cast<float>(r.number(*n, "scale")));
    if (!glm::all(glm::greaterThan(p.scale, glm::vec3(0)))) {
      r.fail(n->source(), "scale must be positive");
    }
  }
  if (const toml::node* n = t.get("rotate_degrees"))
    p.rotate_degrees = r.vec3(*n, "rotate_degrees");
  if (const toml::node* n = t.get("on_ground")) p.on_ground = r.boolean(*n, "on_ground");
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
  r.only_keys(t, {"name", "eye", "target", "up", "fovy_degrees", "near"});
  View v;
  v.name = r.name(r.required(t, "name"), "view name");
  v.eye = r.vec3(r.required(t, "eye"), "eye");
  v.target = r.vec3(r.required(t, "target"), "target");
  if (const toml::node* n = t.get("up")) v.up = r.vec3(*n, "up");
  if (const toml::node* n = t.get("fovy_degrees")) {
    v.fovy_degrees = static_cast<float>(r.number(*n, "fovy_degrees"));
    if (!(v.fovy_degrees > 0 && v.fovy_degrees < 180)) {
      r.fail(n->source(), "fovy_degrees must be in (0, 180)");
    }
  }
  if (const toml::node* n = t.get("near")) v.near = static_cast<float>(r.positive(*n, "near"));
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
  r.only_keys(root, {"name", "meshes", "views"});
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

#include "renderer/scene/scene_file.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>

#include "common/file_io.hpp"
#include "common/printable.hpp"
#include "common/sha256.hpp"
#include "common/toml_reader.hpp"
#include "renderer/scene/mesh_io.hpp"
#include "renderer/scene/view_check.hpp"

namespace aosuite::renderer {
namespace {

namespace fs = std::filesystem;

using SceneReader = TomlReader;

// A [[meshes]] entry's `sha256`: 64 hex digits, as `sha256sum` prints them (either case),
// returned in lowercase as sha256_hex gives them.
std::string sha256_pin(const SceneReader& r, const toml::node& n) {
  std::string hex = r.string(n, "sha256");
  if (hex.size() != 64 || !std::all_of(hex.begin(), hex.end(), [](char c) {
        return std::isxdigit(static_cast<unsigned char>(c));
      })) {
    r.fail(n.source(), fmt::format("sha256 must be 64 hex digits, not '{}'", hex));
  }
  std::transform(hex.begin(), hex.end(), hex.begin(), [](char c) {
    return static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  });
  return hex;
}

// The geometry of one [[meshes]] entry: a file or exactly one built-in primitive.
Mesh mesh_geometry(const SceneReader& r, const toml::table& t) {
  const char* kinds[] = {"file", "box", "sphere", "quad", "plane"};
  const auto given = std::count_if(std::begin(kinds), std::end(kinds),
                                   [&](const char* k) { return t.contains(k); });
  if (given != 1) {
    r.fail(t.source(), "a mesh needs exactly one of file, box, sphere, quad, plane");
  }
  const glm::vec3 colour(0.8f);
  const toml::node* pin = t.get("sha256");
  if (pin && !t.contains("file"))
    r.fail(pin->source(), "sha256 pins a mesh file: this mesh has none");
  if (const toml::node* n = t.get("file")) {
    const fs::path file = r.file().parent_path() / r.string(*n, "file");
    // A malformed pin is refused before the file is read, and a missing file keeps load_mesh's
    // own error, pinned or not. A pinned file is read once: the bytes hashed are those parsed.
    const std::string expected = pin ? sha256_pin(r, *pin) : std::string();
    std::error_code ec;
    const bool pinned = pin && fs::exists(file, ec);
    std::vector<unsigned char> bytes;
    if (pinned) {
      try {
        bytes = read_file(file);
      } catch (const FileError& e) {
        r.fail(n->source(), e.what());
      }
      if (const std::string actual = sha256_hex(bytes); actual != expected) {
        r.fail(pin->source(), fmt::format("{}: SHA-256 is {}, the scene file pins {}",
                                          file.string(), actual, expected));
      }
    }
    try {
      return pinned ? load_mesh(file, std::move(bytes)) : load_mesh(file);
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

// The triangles a [[meshes]] entry makes, known before any geometry is: a sphere's from its
// segments (as make_sphere builds it), a box's 12, a quad's or plane's 2. A mesh file's are
// counted once read (its size bounds what reading it costs).
std::uint64_t predicted_triangles(const SceneReader& r, const toml::table& t) {
  if (const toml::node* n = t.get("sphere"); n && n->is_table()) {
    std::uint64_t segments = 48;
    if (const toml::node* seg = n->as_table()->get("segments")) {
      segments = static_cast<std::uint64_t>(r.integer(*seg, "segments", 4, 1024));
    }
    return 2 * (segments / 2) * segments;
  }
  if (t.contains("box")) return 12;
  if (t.contains("quad") || t.contains("plane")) return 2;
  return 0;
}

Mesh read_mesh(const SceneReader& r, const toml::table& t) {
  r.only_keys(t, {"file", "sha256", "box", "sphere", "quad", "plane", "fit", "scale",
                  "rotate_degrees", "on_ground", "translate", "colour"});
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
  }
  if (const toml::node* n = t.get("near")) v.near = static_cast<float>(r.positive(*n, "near"));
  // What the renderer requires (view_check.hpp), at the key at fault where the file has it.
  if (const auto problem = view_problem(v)) {
    const toml::node* at = t.get(problem->field);
    r.fail(at ? at->source() : t.source(), problem->why);
  }
  // An up along the view direction leaves the camera's roll undefined; the renderer would
  // quietly pick another, a scene file must say what it means.
  const glm::vec3 forward = v.target - v.eye;
  const float dir = glm::length(forward), side = glm::length(glm::cross(forward, v.up));
  if (!(side > 1e-6f * dir * glm::length(v.up))) {
    r.fail(t.source(), "up must not be parallel to the view direction");
  }
  return v;
}

}  // namespace

Scene load_scene_file(const fs::path& path) {
  std::vector<unsigned char> bytes;
  try {
    bytes = read_file(path);
  } catch (const FileError& e) {
    throw FileError(printable(e.what()));  // names the path, escaped
  }
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const SceneReader r(path);
  toml::table root;
  try {
    root = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    r.fail(e.source(), e.description());
  }
  r.only_keys(root, {"name", "family", "meshes", "views"});
  Scene scene;
  scene.name = root.contains("name") ? r.name(*root.get("name"), "name") : path.stem().string();
  if (root.contains("family")) scene.family = r.name(*root.get("family"), "family");
  const std::vector<const toml::table*> meshes = r.tables(r.required(root, "meshes"), "meshes");
  const std::uint64_t limit = max_scene_triangles();
  auto over = [&](const toml::table& t, std::uint64_t triangles) {
    r.fail(t.source(),
           fmt::format("the scene would have {} triangles or more, above the limit of {} "
                       "(AOSUITE_MAX_TRIANGLES sets it)",
                       triangles, limit));
  };
  // Every primitive's triangles are counted before any is made (200 spheres of 1024 segments
  // would be 210 M triangles, 10 GB, from a 14 KB file) ...
  std::uint64_t triangles = 0;
  for (const toml::table* t : meshes) {
    triangles += predicted_triangles(r, *t);
    if (triangles > limit) over(*t, triangles);
  }
  // ... and each mesh file's as it is read.
  for (const toml::table* t : meshes) {
    scene.meshes.push_back(read_mesh(r, *t));
    if (t->contains("file")) {
      triangles += scene.meshes.back().triangles.size();
      if (triangles > limit) over(*t, triangles);
    }
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

std::uint64_t max_scene_triangles() {
  const char* env = std::getenv("AOSUITE_MAX_TRIANGLES");
  if (!env || !*env) return kDefaultMaxSceneTriangles;
  std::uint64_t v = 0;
  const std::string_view text(env);
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v == 0) {
    throw std::invalid_argument(
        printable(fmt::format("AOSUITE_MAX_TRIANGLES='{}' is not a positive integer", text)));
  }
  return v;
}

Scene load_scene(std::string_view name_or_path) {
  if (name_or_path.ends_with(".toml")) return load_scene_file(name_or_path);
  return builtin_scene(name_or_path);
}

}  // namespace aosuite::renderer

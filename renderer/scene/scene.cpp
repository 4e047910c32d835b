#include "renderer/scene/scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

#include "common/cache_dir.hpp"
#include "common/file_io.hpp"
#include "renderer/scene/mesh_io.hpp"

#ifndef AOSUITE_CACHE_DIR
#error "AOSUITE_CACHE_DIR (the repository's .cache) must be defined by the build"
#endif

namespace aosuite::renderer {

Mesh make_quad(glm::vec3 corner, glm::vec3 edge_u, glm::vec3 edge_v, glm::vec3 colour) {
  Mesh m;
  m.colour = colour;
  m.positions = {corner, corner + edge_u, corner + edge_u + edge_v, corner + edge_v};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  compute_normals(m);
  return m;
}

Mesh make_box(glm::vec3 lo, glm::vec3 hi, glm::vec3 colour) {
  const glm::vec3 d = hi - lo;
  const glm::vec3 x(d.x, 0, 0), y(0, d.y, 0), z(0, 0, d.z);
  Mesh m;
  m.colour = colour;
  // Each face on its own vertices so normals stay flat; outward winding.
  append_mesh(m, make_quad(lo, y, x, colour));      // -z
  append_mesh(m, make_quad(lo + z, x, y, colour));  // +z
  append_mesh(m, make_quad(lo, z, y, colour));      // -x
  append_mesh(m, make_quad(lo + x, y, z, colour));  // +x
  append_mesh(m, make_quad(lo, x, z, colour));      // -y
  append_mesh(m, make_quad(lo + y, z, x, colour));  // +y
  return m;
}

Mesh make_gable_roof(glm::vec3 lo, glm::vec3 hi, float height, glm::vec3 colour) {
  const float mz = 0.5f * (lo.z + hi.z), top = hi.y + height;
  const glm::vec3 a(lo.x, hi.y, lo.z), b(hi.x, hi.y, lo.z), c(hi.x, hi.y, hi.z),
      d(lo.x, hi.y, hi.z);
  const glm::vec3 r0(lo.x, top, mz), r1(hi.x, top, mz);
  Mesh m;
  m.colour = colour;
  auto tri = [&](glm::vec3 p, glm::vec3 q, glm::vec3 r) {
    const auto base = static_cast<unsigned>(m.positions.size());
    m.positions.insert(m.positions.end(), {p, q, r});
    m.triangles.push_back({base, base + 1, base + 2});
  };
  tri(a, r0, r1), tri(a, r1, b);  // slope facing -z
  tri(d, c, r1), tri(d, r1, r0);  // slope facing +z
  tri(a, d, r0), tri(b, r1, c);   // gables
  compute_normals(m);             // vertices are not shared, so every face stays flat
  return m;
}

Mesh make_sphere(glm::vec3 centre, float radius, int segments, glm::vec3 colour) {
  Mesh m;
  m.colour = colour;
  const int rings = segments / 2;
  for (int i = 0; i <= rings; ++i) {
    const float theta = glm::pi<float>() * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j <= segments; ++j) {
      const float phi = glm::two_pi<float>() * static_cast<float>(j) / static_cast<float>(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      m.positions.push_back(centre + radius * n);
      m.normals.push_back(n);
    }
  }
  const auto row = static_cast<unsigned>(segments + 1);
  for (unsigned i = 0; i < static_cast<unsigned>(rings); ++i) {
    for (unsigned j = 0; j < static_cast<unsigned>(segments); ++j) {
      const unsigned a = i * row + j, b = a + row;
      m.triangles.push_back({a, a + 1, b});
      m.triangles.push_back({a + 1, b + 1, b});
    }
  }
  return m;
}

namespace {

// Bounding box of the vertices triangles use (scans often carry stray unused vertices).
std::pair<glm::vec3, glm::vec3> triangle_bounds(const Mesh& mesh) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::uvec3& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      lo = glm::min(lo, mesh.positions[t[k]]);
      hi = glm::max(hi, mesh.positions[t[k]]);
    }
  }
  return {lo, hi};
}

void transform_mesh(Mesh& mesh, const glm::mat4& m) {
  // The inverse transpose of the linear part, scaled first to unit size (normals are made unit
  // after, so the scale changes no bit): fitting a mesh 1e15 units wide scales by 1e-15, whose
  // determinant, 1e-45, underflows float, and the inverse was Inf.
  glm::mat3 linear(m);
  linear *= unit_scale(std::span<const glm::vec3>(&linear[0], 3));
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(linear));
  for (glm::vec3& p : mesh.positions) p = glm::vec3(m * glm::vec4(p, 1));
  for (glm::vec3& n : mesh.normals) {
    const glm::vec3 t = normal_matrix * n;
    const float len = glm::length(t);
    n = len > 0 && std::isfinite(len) ? t / len : glm::vec3(0, 1, 0);
  }
}

}  // namespace

void place_mesh(Mesh& mesh, const Placement& p) {
  if (!(glm::all(glm::greaterThan(p.scale, glm::vec3(0))) && std::isfinite(p.scale.x) &&
        std::isfinite(p.scale.y) && std::isfinite(p.scale.z))) {
    throw std::invalid_argument("scale must be positive and finite");
  }
  glm::mat4 m(1);
  if (p.fit) {
    const auto [lo, hi] = triangle_bounds(mesh);
    const glm::vec3 size = hi - lo;
    const float extent = std::max({size.x, size.y, size.z});
    if (!(*p.fit > 0 && extent > 0 && std::isfinite(extent))) {
      throw std::invalid_argument(
          "cannot fit: the size must be positive and the mesh must have "
          "a non-zero extent");
    }
    m = glm::scale(glm::mat4(1), glm::vec3(*p.fit / extent)) *
        glm::translate(glm::mat4(1), -0.5f * (lo + hi));
  }
  const glm::vec3 r = glm::radians(p.rotate_degrees);
  m = glm::rotate(glm::mat4(1), r.z, {0, 0, 1}) * glm::rotate(glm::mat4(1), r.y, {0, 1, 0}) *
      glm::rotate(glm::mat4(1), r.x, {1, 0, 0}) * glm::scale(glm::mat4(1), p.scale) * m;
  transform_mesh(mesh, m);
  glm::vec3 shift = p.translate;
  if (p.on_ground && !mesh.triangles.empty()) shift.y -= triangle_bounds(mesh).first.y;
  for (glm::vec3& v : mesh.positions) v += shift;
  for (const glm::vec3& v : mesh.positions) {
    if (!std::isfinite(v.x + v.y + v.z)) {
      throw std::invalid_argument("the placement makes a vertex position non-finite");
    }
  }
}

void scale_scene(Scene& scene, float factor) {
  for (Mesh& m : scene.meshes) {
    for (glm::vec3& p : m.positions) p *= factor;
  }
  for (View& v : scene.views) {
    v.eye *= factor;
    v.target *= factor;
    v.near *= factor;
  }
}

namespace {

const glm::vec3 kGround(0.55f, 0.6f, 0.5f), kWall(0.85f, 0.8f, 0.7f), kRoof(0.6f, 0.3f, 0.25f),
    kWood(0.55f, 0.4f, 0.25f), kIron(0.35f, 0.35f, 0.38f);

Mesh ground(float half) {
  Mesh m = make_quad({-half, 0, -half}, {0, 0, 2 * half}, {2 * half, 0, 0}, kGround);
  m.ground = true;
  return m;
}

Scene plane() {
  return {"plane",
          {ground(50)},
          {{"above", {0, 3, 6}, {0, 0, 0}}, {"grazing", {0, 0.3f, 8}, {0, 0, -10}}}};
}

Scene corner() {
  Scene s{"corner",
          {ground(20)},
          {{"inside", {3, 2.5f, 3}, {0, 0.3f, 0}}, {"front", {0.5f, 1.5f, 6}, {0, 0.5f, 0}}}};
  s.meshes.push_back(make_quad({-20, 0, 0}, {40, 0, 0}, {0, 20, 0}, kWall));  // wall at z = 0
  return s;
}

Scene spheres() {
  Scene s{"spheres",
          {ground(30)},
          {{"front", {0, 2, 7}, {0, 0.5f, 0}}, {"top", {0.5f, 8, 0.5f}, {0, 0, 0}}}};
  s.meshes.push_back(make_sphere({-1.5f, 1, 0}, 1, 48, {0.8f, 0.5f, 0.4f}));
  s.meshes.push_back(make_sphere({1.2f, 0.6f, 0.5f}, 0.6f, 40, {0.4f, 0.6f, 0.8f}));
  s.meshes.push_back(make_sphere({0.2f, 0.3f, 2}, 0.3f, 32, {0.9f, 0.85f, 0.4f}));
  return s;
}

// Six two-storey houses along a street (the thesis's open-space scene).
Scene village() {
  Scene s{"village", {ground(80)}, {}};
  for (int i = 0; i < 6; ++i) {
    const float x = -15.0f + 10.0f * static_cast<float>(i % 3), z = i < 3 ? -9.0f : 9.0f;
    const glm::vec3 lo(x - 3.5f, 0, z - 3), hi(x + 3.5f, 6, z + 3);  // two storeys of 3 m
    s.meshes.push_back(make_box(lo, hi, kWall));
    s.meshes.push_back(
        make_gable_roof(lo - glm::vec3(0.4f, 0, 0.4f), hi + glm::vec3(0.4f, 0, 0.4f), 2.5f, kRoof));
    s.meshes.push_back(make_box({x - 0.6f, 0, z + (z < 0 ? 3 : -3.3f)},
                                {x + 0.6f, 2.2f, z + (z < 0 ? 3.3f : -3)}, kWood));
  }
  s.views = {{"street", {-24, 1.7f, 1}, {0, 3, 0}}, {"overview", {22, 20, 26}, {0, 2, 0}}};
  return s;
}

// A smithy: a walled room with a door, an anvil, a forge and a bench inside, a yard outside
// (stands in for the thesis's blacksmith scene).
Scene workshop() {
  Scene s{"workshop", {ground(40)}, {}};
  const float w = 6, d = 5, h = 3.5f, t = 0.25f;
  s.meshes.push_back(make_box({-w, 0, -d}, {w, h, -d + t}, kWall));   // back
  s.meshes.push_back(make_box({-w, 0, -d}, {-w + t, h, d}, kWall));   // left
  s.meshes.push_back(make_box({w - t, 0, -d}, {w, h, d}, kWall));     // right
  s.meshes.push_back(make_box({-w, 0, d - t}, {-1, h, d}, kWall));    // front, left of door
  s.meshes.push_back(make_box({1, 0, d - t}, {w, h, d}, kWall));      // front, right of door
  s.meshes.push_back(make_box({-1, 2.4f, d - t}, {1, h, d}, kWall));  // lintel
  s.meshes.push_back(
      make_box({-w - 0.3f, h, -d - 0.3f}, {w + 0.3f, h + 0.2f, 0}, kRoof));    // half roof
  s.meshes.push_back(make_box({-0.4f, 0, -0.2f}, {0.4f, 0.6f, 0.2f}, kIron));  // anvil block
  s.meshes.push_back(make_box({-0.7f, 0.6f, -0.25f}, {0.7f, 0.85f, 0.25f}, kIron));
  s.meshes.push_back(make_box({-5, 0, -4.6f}, {-2.5f, 1.2f, -3}, {0.5f, 0.45f, 0.42f}));  // forge
  s.meshes.push_back(make_box({2.5f, 0.9f, -4.7f}, {5.5f, 1, -3.7f}, kWood));  // bench top
  for (float lx : {2.6f, 5.3f}) {
    s.meshes.push_back(make_box({lx, 0, -4.6f}, {lx + 0.12f, 0.9f, -4.45f}, kWood));
    s.meshes.push_back(make_box({lx, 0, -3.95f}, {lx + 0.12f, 0.9f, -3.8f}, kWood));
  }
  s.meshes.push_back(make_box({3, 0, 7}, {4.2f, 0.9f, 8.2f}, kWood));  // crates outside
  s.meshes.push_back(make_box({3.2f, 0.9f, 7.2f}, {4, 1.7f, 8}, kWood));
  s.meshes.push_back(make_sphere({-3, 0.5f, 8}, 0.5f, 32, kWood));  // barrel-ish
  s.views = {{"interior", {4.5f, 1.7f, 3.5f}, {-1, 0.8f, -3}},
             {"exterior", {9, 4, 14}, {0, 1.5f, 2}}};
  return s;
}

// The Stanford dragon (Stanford's vrip reconstruction, decimated to 47,794 triangles, near the
// thesis's 16,191) fitted to 5 m long on a ground plane; views as in the thesis: close enough
// to see the scales, and from a distance.
constexpr std::string_view kDragonFile = "dragon_vrip_res3.ply";

std::vector<View> dragon_views() {
  return {{"close", {3.2f, 2.4f, 4.2f}, {0, 1.2f, 0}}, {"far", {-9, 5, 14}, {0, 1.5f, 0}}};
}

Scene dragon() {
  const std::filesystem::path file = downloadable_scene_file("dragon");
  if (!std::filesystem::exists(file)) {
    throw FileError(fmt::format(
        "{}: not found; the dragon scene needs it: run scripts/fetch_assets.sh", file.string()));
  }
  Mesh mesh = load_mesh(file);
  mesh.colour = {0.75f, 0.7f, 0.6f};
  Placement p;
  p.fit = 5;
  p.on_ground = true;
  place_mesh(mesh, p);
  Scene s{"dragon", {ground(40)}, dragon_views()};
  s.meshes.push_back(std::move(mesh));
  return s;
}

struct Builtin {
  std::string_view name;
  Scene (*make)();
  std::vector<View> (*downloaded_views)();  // set for scenes that need a download
  std::string_view family;                  // Scene::family
};
// Plane to workshop are made of boxes, quads and spheres in code; the dragon is a scan.
constexpr Builtin kBuiltins[] = {
    {"plane", plane, nullptr, "analytic"},       {"corner", corner, nullptr, "analytic"},
    {"spheres", spheres, nullptr, "analytic"},   {"village", village, nullptr, "analytic"},
    {"workshop", workshop, nullptr, "analytic"}, {"dragon", dragon, dragon_views, "scan"}};

const Builtin& find_builtin(std::string_view name) {
  for (const Builtin& b : kBuiltins) {
    if (b.name == name) return b;
  }
  std::string names;
  for (const Builtin& b : kBuiltins) names += (names.empty() ? "" : ", ") + std::string(b.name);
  throw std::invalid_argument("unknown scene '" + std::string(name) + "' (built in: " + names +
                              "; or a .toml scene file)");
}

std::vector<std::string> builtin_names(bool downloaded) {
  std::vector<std::string> names;
  for (const Builtin& b : kBuiltins) {
    if ((b.downloaded_views != nullptr) == downloaded) names.emplace_back(b.name);
  }
  return names;
}

}  // namespace

std::vector<std::string> builtin_scene_names() { return builtin_names(false); }
std::vector<std::string> downloadable_scene_names() { return builtin_names(true); }

std::filesystem::path downloadable_scene_file(std::string_view name) {
  if (name != "dragon") throw std::invalid_argument(fmt::format("'{}' needs no download", name));
  const char* env = std::getenv("AOSUITE_ASSETS");
  const std::filesystem::path dir =
      env && *env ? std::filesystem::path(env) : cache_dir(AOSUITE_CACHE_DIR) / "assets";
  return dir / kDragonFile;
}

Scene builtin_scene(std::string_view name) {
  const Builtin& b = find_builtin(name);
  Scene s = b.make();
  s.family = b.family;
  return s;
}

std::vector<View> builtin_scene_views(std::string_view name) {
  const Builtin& b = find_builtin(name);
  return b.downloaded_views ? b.downloaded_views() : b.make().views;
}

const View& find_view(const Scene& scene, std::string_view name) {
  if (scene.views.empty()) throw std::invalid_argument("scene '" + scene.name + "' has no views");
  if (name.empty()) return scene.views.front();
  for (const View& v : scene.views) {
    if (v.name == name) return v;
  }
  std::size_t index = 0;
  const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), index);
  if (ec == std::errc() && end == name.data() + name.size() && index < scene.views.size()) {
    return scene.views[index];
  }
  std::string names;
  for (const View& v : scene.views) names += (names.empty() ? "" : ", ") + v.name;
  throw std::invalid_argument("scene '" + scene.name + "' has no view '" + std::string(name) +
                              "' (views: " + names + ")");
}

}  // namespace aosuite::renderer

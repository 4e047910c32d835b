// Scenes: triangle meshes in world space with a colour each, and named camera views.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "renderer/scene/mesh.hpp"

namespace aosuite::renderer {

struct View {
  std::string name;
  glm::vec3 eye{0, 1, 5};
  glm::vec3 target{0, 0, 0};
  glm::vec3 up{0, 1, 0};
  float fovy_degrees = 60;
  float near = 0.05f;  // the far plane is at infinity (reversed-Z depth)
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<View> views;
  // The kind of scene ("analytic", "scan", "architecture", "cad"...): `aosuite tune` validates
  // by leaving a whole family out at a time, since scenes of one kind share their scale and
  // structure and would flatter a preset fitted to them. Empty: a family of its own.
  std::string family = {};
};

// Geometry builders, all with normals.
Mesh make_box(glm::vec3 min, glm::vec3 max, glm::vec3 colour);
Mesh make_quad(glm::vec3 corner, glm::vec3 edge_u, glm::vec3 edge_v, glm::vec3 colour);
Mesh make_sphere(glm::vec3 centre, float radius, int segments, glm::vec3 colour);
// A gable roof (triangular prism) over the box min..max, ridge along x, `height` above max.y.
Mesh make_gable_roof(glm::vec3 min, glm::vec3 max, float height, glm::vec3 colour);

// Where a mesh goes, applied in this order: fit (centre the bounding box of its triangles on
// the origin and scale it uniformly so its longest side is `fit`: scanned meshes come in
// unknown units), scale (per axis, positive), rotate (degrees about x, then y, then z),
// on_ground (lift or lower it so its lowest point is at y = 0), translate.
struct Placement {
  std::optional<float> fit;
  glm::vec3 scale{1};
  glm::vec3 rotate_degrees{0};
  bool on_ground = false;
  glm::vec3 translate{0};
};
// Moves positions and normals (by the inverse transpose, so per-axis scales keep them
// perpendicular). Throws std::invalid_argument for a mesh with no extent to fit, a scale that
// is not positive, or a result that is not finite.
void place_mesh(Mesh& mesh, const Placement& placement);

// Uniform scaling of every mesh and view about the origin (stress tests of scene scale).
void scale_scene(Scene& scene, float factor);

// Built-in scenes that need no download: "plane", "corner", "spheres" (analytic tests),
// "village" (six two-storey houses, open space), "workshop" (interior and exterior).
std::vector<std::string> builtin_scene_names();
// Built-in scenes whose mesh scripts/fetch_assets.sh downloads: "dragon" (the Stanford dragon
// on a ground plane, as in the thesis).
std::vector<std::string> downloadable_scene_names();
// The file a downloadable scene needs: in $AOSUITE_ASSETS when set, else in the repository's
// .cache/assets/ (compiled in, so any working directory finds it).
std::filesystem::path downloadable_scene_file(std::string_view name);
// Throws std::invalid_argument if unknown, aosuite::FileError if a download is missing.
Scene builtin_scene(std::string_view name);
// A built-in scene's views without loading its meshes (for listings).
std::vector<View> builtin_scene_views(std::string_view name);

// The view called `name`, or the view at index `name` ("0", "1"), or the first view when
// `name` is empty; throws std::invalid_argument naming the scene's views otherwise.
const View& find_view(const Scene& scene, std::string_view name);

}  // namespace aosuite::renderer

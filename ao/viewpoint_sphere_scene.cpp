#include "ao/viewpoint_sphere_scene.hpp"

#include <algorithm>

#include "renderer/pmi/viewpoint_sphere.hpp"

namespace aosuite::ao {
namespace {

namespace rd = aosuite::renderer;

// Cold (low) to warm (high), as the paper's spheres.
glm::vec3 heat(float t) {
  const glm::vec3 stops[] = {
      {0.1f, 0.2f, 0.9f}, {0.1f, 0.8f, 0.9f}, {0.95f, 0.9f, 0.2f}, {0.9f, 0.15f, 0.1f}};
  const float x = std::clamp(t, 0.0f, 1.0f) * 3;
  const int i = std::min(2, static_cast<int>(x));
  return glm::mix(stops[i], stops[i + 1], x - static_cast<float>(i));
}

}  // namespace

rd::Scene coloured_sphere(const std::vector<glm::vec3>& directions,
                          const std::vector<double>& value) {
  const auto [lo, hi] = std::minmax_element(value.begin(), value.end());
  const rd::Icosphere fine = rd::make_icosphere(
      std::min<int>(2562, static_cast<int>(directions.size()) * 16 - 30));  // two more subdivisions
  constexpr int kBands = 64;
  rd::Scene s{"viewpoint_sphere", std::vector<rd::Mesh>(kBands), {}};
  for (const glm::uvec3& f : fine.faces) {
    const glm::vec3 c =
        glm::normalize(fine.vertices[f.x] + fine.vertices[f.y] + fine.vertices[f.z]);
    std::size_t nearest = 0;
    for (std::size_t v = 1; v < directions.size(); ++v)
      if (glm::dot(c, directions[v]) > glm::dot(c, directions[nearest])) nearest = v;
    const double t = *hi > *lo ? (value[nearest] - *lo) / (*hi - *lo) : 0.5;
    rd::Mesh& band = s.meshes[std::min(kBands - 1, static_cast<int>(t * kBands))];
    const auto base = static_cast<unsigned>(band.positions.size());
    for (unsigned i : {f.x, f.y, f.z}) band.positions.push_back(fine.vertices[i]);
    band.triangles.emplace_back(base, base + 1, base + 2);
  }
  for (int b = 0; b < kBands; ++b) {
    s.meshes[b].colour = heat((static_cast<float>(b) + 0.5f) / kBands);
    rd::compute_normals(s.meshes[b]);
  }
  return s;
}

}  // namespace aosuite::ao

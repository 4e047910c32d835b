#include "renderer/scene/mesh.hpp"

#include <cmath>

namespace aosuite::renderer {

void compute_normals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0));
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::vec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
    const glm::vec3 n = glm::cross(b - a, c - a);  // length = twice the area: area weighting
    if (!std::isfinite(n.x + n.y + n.z)) continue;
    mesh.normals[t.x] += n, mesh.normals[t.y] += n, mesh.normals[t.z] += n;
  }
  for (glm::vec3& n : mesh.normals) {
    const float len = glm::length(n);
    n = len > 0 && std::isfinite(len) ? n / len : glm::vec3(0, 1, 0);
  }
}

void append_mesh(Mesh& into, const Mesh& part) {
  const auto base = static_cast<unsigned>(into.positions.size());
  into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
  into.normals.insert(into.normals.end(), part.normals.begin(), part.normals.end());
  for (const glm::uvec3& t : part.triangles) into.triangles.push_back(t + glm::uvec3(base));
}

}  // namespace aosuite::renderer

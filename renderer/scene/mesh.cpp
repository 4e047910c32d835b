#include "renderer/scene/mesh.hpp"

#include <algorithm>
#include <cmath>

namespace aosuite::renderer {

float unit_scale(std::span<const glm::vec3> values) {
  float largest = 0;
  for (const glm::vec3& v : values) {
    for (int k = 0; k < 3; ++k) {
      if (std::isfinite(v[k])) largest = std::max(largest, std::abs(v[k]));
    }
  }
  return largest > 0 ? std::ldexp(1.0f, -std::ilogb(largest)) : 1.0f;
}

void compute_normals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0));
  // Positions scaled to [1, 2) by a power of two, which changes no bit of the normals, so the
  // cross products and their squared lengths can neither overflow nor underflow for a mesh
  // 1e15 or 1e-15 units wide (before, its every normal fell back to +y: a flat shade).
  const float s = unit_scale(mesh.positions);
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::vec3 a = mesh.positions[t.x] * s, b = mesh.positions[t.y] * s,
                    c = mesh.positions[t.z] * s;
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

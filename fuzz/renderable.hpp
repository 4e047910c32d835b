// The property every mesh a loader hands the renderer must have (mesh and scene targets).
#pragma once

#include <cmath>

#include "fuzz/fuzz_util.hpp"
#include "renderer/scene/scene.hpp"

namespace aosuite::fuzz {

// What the renderer relies on in every mesh a loader returns: triangles index existing
// vertices, one finite normal per vertex, finite positions.
inline void expect_renderable(const renderer::Mesh& m) {
  if (m.normals.size() != m.positions.size()) fail("normals and positions differ in count");
  for (const glm::uvec3& t : m.triangles) {
    if (t.x >= m.positions.size() || t.y >= m.positions.size() || t.z >= m.positions.size()) {
      fail("a triangle indexes past the vertices");
    }
  }
  auto finite = [](const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  for (const glm::vec3& p : m.positions) {
    if (!finite(p)) fail("a position is not finite");
  }
  for (const glm::vec3& n : m.normals) {
    if (!finite(n)) fail("a normal is not finite");
  }
}

}  // namespace aosuite::fuzz

// The viewpoint sphere of viewpoint-based AO: a recursively subdivided icosahedron.
#pragma once

#include <glm/glm.hpp>
#include <vector>

namespace aosuite::renderer {

struct Icosphere {
  std::vector<glm::vec3> vertices;  // unit length
  std::vector<glm::uvec3> faces;    // counter-clockwise seen from outside
};

// The icosahedron subdivided until it has `vertex_count` = 10 * 4^k + 2 vertices (12, 42, 162,
// 642, 2562); throws std::invalid_argument for any other count.
Icosphere make_icosphere(int vertex_count);

}  // namespace aosuite::renderer

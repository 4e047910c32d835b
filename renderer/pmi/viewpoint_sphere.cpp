#include "renderer/pmi/viewpoint_sphere.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace aosuite::renderer {
namespace {

Icosphere icosahedron() {
  const float t = (1 + std::sqrt(5.0f)) / 2;
  Icosphere s;
  s.vertices = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (glm::vec3& v : s.vertices) v = glm::normalize(v);
  s.faces = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  return s;
}

// Splits every face into four, sharing each edge's new midpoint between its two faces.
void subdivide(Icosphere& s) {
  std::map<std::pair<unsigned, unsigned>, unsigned> midpoints;
  auto midpoint = [&](unsigned a, unsigned b) {
    const auto key = std::minmax(a, b);
    auto [it, fresh] = midpoints.try_emplace(key, static_cast<unsigned>(s.vertices.size()));
    if (fresh) s.vertices.push_back(glm::normalize(s.vertices[a] + s.vertices[b]));
    return it->second;
  };
  std::vector<glm::uvec3> faces;
  faces.reserve(s.faces.size() * 4);
  for (const glm::uvec3& f : s.faces) {
    const unsigned ab = midpoint(f.x, f.y);
    const unsigned bc = midpoint(f.y, f.z);
    const unsigned ca = midpoint(f.z, f.x);
    for (const glm::uvec3 child : {glm::uvec3(f.x, ab, ca), glm::uvec3(f.y, bc, ab),
                                   glm::uvec3(f.z, ca, bc), glm::uvec3(ab, bc, ca)})
      faces.push_back(child);
  }
  s.faces = std::move(faces);
}

}  // namespace

Icosphere make_icosphere(int vertex_count) {
  Icosphere s = icosahedron();
  while (static_cast<int>(s.vertices.size()) < vertex_count && s.vertices.size() < 2562)
    subdivide(s);
  if (static_cast<int>(s.vertices.size()) != vertex_count) {
    throw std::invalid_argument("viewpoints=" + std::to_string(vertex_count) +
                                ": expected 12, 42, 162, 642 or 2562 (a subdivided icosahedron)");
  }
  return s;
}

}  // namespace aosuite::renderer

// A triangle mesh as every scene source produces it (built-in builders, mesh files, scene
// files) and the G-buffer pass draws it.
#pragma once

#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace aosuite::renderer {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // per vertex; computed when a loader has none
  std::vector<glm::uvec3> triangles;
  glm::vec3 colour{0.8f};
  // A ground plane: not part of "the object" for object-space techniques (PMI), whose
  // viewpoint sphere a 40 m plane would swallow.
  bool ground = false;
};

// The power of two that brings the largest finite |component| of `values` to [1, 2) (1 when
// all are 0): scaling by it is exact, so a computation scaled by it gives the same bits, out of
// reach of float's overflow and underflow.
float unit_scale(std::span<const glm::vec3> values);

// Area-weighted vertex normals; zero-area triangles contribute nothing and a vertex with no
// usable triangle gets +y, so no NaN ever reaches the G-buffer.
void compute_normals(Mesh& mesh);

// Appends `part`'s vertices and triangles to `into` (its colour is not changed).
void append_mesh(Mesh& into, const Mesh& part);

}  // namespace aosuite::renderer

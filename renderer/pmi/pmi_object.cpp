#include "renderer/pmi/pmi_object.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace aosuite::renderer {

PmiObject pmi_object(const Scene& scene) {
  PmiObject o;
  for (const Mesh& m : scene.meshes) {
    if (m.ground) {
      o.mesh_vertex_base.push_back(-1);
      continue;
    }
    const auto base = static_cast<unsigned>(o.positions.size());
    o.mesh_vertex_base.push_back(static_cast<int>(base));
    o.positions.insert(o.positions.end(), m.positions.begin(), m.positions.end());
    const std::size_t n = m.positions.size();
    for (const glm::uvec3& t : m.triangles) {
      if (t.x >= n || t.y >= n || t.z >= n) continue;
      const glm::vec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
      if (!std::isfinite(a.x + a.y + a.z + b.x + b.y + b.z + c.x + c.y + c.z)) continue;
      o.triangles.push_back(t + glm::uvec3(base));
    }
  }
  if (o.triangles.empty()) {
    throw std::invalid_argument("scene '" + scene.name +
                                "' has no object for pmi: every mesh is a ground plane");
  }
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::uvec3& t : o.triangles) {
    for (unsigned i : {t.x, t.y, t.z})
      lo = glm::min(lo, o.positions[i]), hi = glm::max(hi, o.positions[i]);
  }
  o.centre = 0.5f * (lo + hi);
  for (const glm::uvec3& t : o.triangles) {
    for (unsigned i : {t.x, t.y, t.z})
      o.radius = std::max(o.radius, glm::length(o.positions[i] - o.centre));
  }
  // A single point: any positive radius frames it.
  if (!(o.radius > 0)) o.radius = 1;
  return o;
}

View viewpoint_view(const PmiObject& o, glm::vec3 eye) {
  View v;
  v.name = "viewpoint";
  v.eye = eye, v.target = o.centre;
  const glm::vec3 forward = glm::normalize(o.centre - eye);
  v.up = std::abs(forward.y) > 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  const float distance = glm::length(o.centre - eye);
  v.fovy_degrees = glm::degrees(2 * std::asin(std::min(1.0f, 1.01f * o.radius / distance)));
  v.near = std::max(distance - 1.01f * o.radius, distance * 1e-3f);
  return v;
}

float viewpoint_far(const PmiObject& o, glm::vec3 eye) {
  return glm::length(o.centre - eye) + 1.01f * o.radius;
}

}  // namespace aosuite::renderer

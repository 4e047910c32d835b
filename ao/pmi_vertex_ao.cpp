#include "ao/pmi_vertex_ao.hpp"

#include "reference/reference_ao.hpp"

namespace aosuite::ao {

std::vector<float> ray_traced_vertex_ao(const renderer::PmiObject& o,
                                        const std::vector<glm::vec3>& normals, int rays) {
  renderer::Scene object;
  object.meshes.push_back({o.positions, normals, o.triangles});
  const reference::EmbreeScene scene(object);
  reference::ReferenceSettings s;
  s.rays = rays, s.variant = reference::Variant::kUnbounded;
  reference::validate(s);

  std::vector<bool> used(o.positions.size(), false);
  for (const glm::uvec3& t : o.triangles) used[t.x] = used[t.y] = used[t.z] = true;
  const float offset = 1e-4f * o.radius;  // off the surface, past float error
  std::vector<float> ao(o.positions.size(), 1.0f);
  for (std::size_t i = 0; i < o.positions.size(); ++i) {
    if (!used[i]) continue;
    const glm::vec3 n =
        glm::length(normals[i]) > 0 ? glm::normalize(normals[i]) : glm::vec3(0, 1, 0);
    ao[i] = reference::occlusion_at(scene, o.positions[i] + offset * n, n, i, s);
  }
  return ao;
}

}  // namespace aosuite::ao

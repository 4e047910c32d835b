// The object that viewpoint-based AO looks at, and the camera of one viewpoint on its sphere:
// what the item buffer renders and the channel accumulates (pmi_item_buffer, pmi_channel).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "renderer/scene/scene.hpp"

namespace aosuite::renderer {

// The object's polygons: the scene's non-ground meshes concatenated (triangles with an index
// out of range or a non-finite corner are left out, as the G-buffer pass leaves them out).
struct PmiObject {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;
  std::vector<int> mesh_vertex_base;  // per scene mesh: its first vertex here; -1 for ground
  glm::vec3 centre{0};
  float radius = 0;  // bounding sphere about `centre`
};
// Throws std::invalid_argument when the scene has no non-ground triangle.
PmiObject pmi_object(const Scene& scene);

// The camera of the viewpoint at `eye`: looking at the object's centre, its vertical field of
// view just holding the bounding sphere, its near plane just in front of it.
View viewpoint_view(const PmiObject& object, glm::vec3 eye);
// The far plane that goes with it: just behind the bounding sphere.
float viewpoint_far(const PmiObject& object, glm::vec3 eye);

}  // namespace aosuite::renderer

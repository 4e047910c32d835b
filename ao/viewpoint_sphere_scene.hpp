// The viewpoint sphere of `aosuite viewpoints` as a scene to render: one cell per viewpoint
// (faces of a finer sphere coloured by their nearest viewpoint), coloured cold (low) to warm
// (high) by a value per viewpoint, as the PMI paper's spheres.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "renderer/scene/scene.hpp"

namespace aosuite::ao {

// `directions`: unit vectors from the object's centre, one per viewpoint, `value` beside them;
// 64 colour bands, one mesh per band.
renderer::Scene coloured_sphere(const std::vector<glm::vec3>& directions,
                                const std::vector<double>& value);

}  // namespace aosuite::ao

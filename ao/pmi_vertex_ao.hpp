// The classic AO the PMI paper compares with, per vertex of PMI's object: the share of
// cosine-weighted hemisphere rays around the vertex normal that escape the object (unbounded
// distance, the object alone: PMI also sees only the object), ray traced with Embree 3.
#pragma once

#include <vector>

#include "renderer/pmi/pmi_channel.hpp"

namespace aosuite::ao {

// `normals` per object vertex; `rays` per vertex (the reference's cosine-weighted Hammersley
// directions, rotated per vertex index, so the result is reproducible). Vertices in no
// triangle get 1.
std::vector<float> ray_traced_vertex_ao(const renderer::PmiObject& object,
                                        const std::vector<glm::vec3>& normals, int rays);

}  // namespace aosuite::ao

// How smooth an AO is, for the PMI paper's smoothness claim (`aosuite pmi-study`): per vertex
// of PMI's object (distinct values, steps across mesh edges) and per pixel of a rendered AO
// term (distinct 8-bit levels, steps between neighbours).
#pragma once

#include <cstddef>
#include <vector>

#include "renderer/pmi/pmi_channel.hpp"
#include "renderer/renderer.hpp"

namespace aosuite::ao {

struct Smoothness {
  std::size_t distinct = 0;
  double mean_step = 0, flat_edges = 0;  // mean |difference| across an edge; share that are 0
};

// The per-vertex values of the vertices some triangle uses (the others are not the object's).
std::vector<double> used_vertex_values(const renderer::PmiObject& o, const std::vector<float>& v);

Smoothness vertex_smoothness(const renderer::PmiObject& o, const std::vector<float>& v);

// Over geometry pixels: distinct 8-bit AO levels and the mean |horizontal and vertical step|
// (flat_edges unused).
Smoothness image_smoothness(const renderer::Images& img);

}  // namespace aosuite::ao

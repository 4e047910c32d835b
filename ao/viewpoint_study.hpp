// Viewpoint selection with PMI's channel (González et al. 2008), `aosuite viewpoints`: VMI
// I(v;O) and PMI(v) = sum_o p(v|o) PMI(o) per viewpoint, the most and least informative views
// (by PMI(v), as the paper's Figure 6: the best sees the most PMI) and the viewpoint sphere
// coloured by PMI(v), cold to warm, from the front (+z) and the back.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace aosuite::ao {

struct ViewpointStudySettings {
  std::string scene = "dragon", out = "reports/viewpoints";
  // importance_best 0: p(v) by projected area; k: the k best views share 99 %. width x height:
  // the view images'.
  int viewpoints = 162, resolution = 1280, importance_best = 0, width = 640, height = 480;
  bool colour_ao = false;  // also write colour AO as a PLY (ao/colour_ao_ply.hpp)
};

// Writes per-viewpoint CSV, the best and worst views, the sphere (PNG) and the summary (JSON)
// into `out`; returns the summary.
nlohmann::ordered_json run_viewpoint_study(const ViewpointStudySettings& a);

}  // namespace aosuite::ao

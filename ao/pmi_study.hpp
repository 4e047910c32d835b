// The PMI paper's Table 1 study (item-buffer resolution x viewpoints: time and quality) and
// its smoothness claim, on one scene's object (`aosuite pmi-study`):
//  - time of each channel (wall clock, llvmpipe);
//  - quality per vertex against ray-traced unbounded AO of the object (Embree, cosine-weighted,
//    `rays` per vertex): Pearson and Spearman correlation (PMI is normalised differently from
//    AO, so agreement is measured up to a monotone map), and the mean absolute difference from
//    the largest case's map (convergence);
//  - smoothness per vertex (distinct values, differences across mesh edges) and per pixel of
//    the rendered AO (distinct 8-bit levels, mean gradient) beside the screen-space techniques.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace aosuite::ao {

struct PmiStudySettings {
  std::string scene = "dragon", view, out = "reports/pmi-study";
  std::vector<int> resolutions{640, 1280, 2560}, viewpoints{12, 42, 162, 642};  // item buffers
  int rays = 256, width = 480, height = 270;  // the rendered comparison's size
};

// The study can take minutes: it reports each step as it ends.
struct PmiStudyProgress {
  std::function<void(const std::string& scene, std::size_t polygons, std::size_t vertices,
                     double seconds)>
      traced;  // the ray-traced per-vertex AO
  std::function<void(int width, int height, int viewpoints, double seconds)> measured;  // a PMI
};

// Writes the rendered AO images (PNG) and pmi_study.md into `out`; returns the Markdown.
std::string run_pmi_study(const PmiStudySettings& a, const PmiStudyProgress& progress);

}  // namespace aosuite::ao

// One configuration's result in `aosuite sweep`, and its JSON form, which shards write and
// `sweep --merge` reads back.
#pragma once

#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "reference/error_metrics.hpp"
#include "reference/frame_error.hpp"
#include "renderer/technique.hpp"

namespace aosuite::ao {

struct Row {
  std::size_t index = 0;  // the configuration's place in the grid's order
  std::string scene, view;
  std::size_t view_index = 0;
  renderer::Technique technique{};
  int width = 0, height = 0, samples = 0;
  float radius = 0, intensity = 0;
  double gl_ms = 0;  // the AO passes' GPU time (median of the runs)
  // Pixels that drew geometry: 0 when the view sees none, whose errors are then of the
  // background alone (`sweep` warns).
  int geometry_pixels = 0;
  reference::ErrorReport error;
  reference::ErrorStats unbounded;
  reference::FrameError frame;  // the final image's FLIP and SSIM against the reference's
  std::map<std::string, std::string> params;  // the grid's fixed parameters
};

// The grid's fixed parameters as text: "blur=none level_weights=1,0,0,0,0".
std::string params_text(const Row& r);
// The technique as the console and Markdown name it: "mssao (max_pixel_radius=10)".
std::string row_label(const Row& r);

nlohmann::ordered_json row_json(const Row& r, bool unbounded);
// Throws std::invalid_argument (or nlohmann's errors) for a row that row_json did not write.
Row row_from_json(const nlohmann::json& j);

}  // namespace aosuite::ao

// `aosuite error`'s measurement: one technique's AO term (Images::ao, after its default blur)
// against the ray-traced reference at the technique's radius, on the same G-buffer pixels
// (RMSE, MAE, bias, PSNR and SSIM over all, depth-edge and interior pixels), and the final
// image's FLIP and SSIM against the same frame shaded with the reference
// (reference/frame_error.hpp).
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "ao/case_options.hpp"
#include "reference/error_metrics.hpp"
#include "reference/frame_error.hpp"
#include "reference/reference_ao.hpp"
#include "renderer/renderer.hpp"

namespace aosuite::ao {

struct ErrorStudy {
  std::string scene, view;
  renderer::RenderSettings settings;
  reference::ReferenceSettings reference_settings;
  bool reference_cached = false;  // read from the reference cache rather than traced
  double reference_seconds = 0;   // the tracing time of the cache's last miss
  cv::Mat ao, reference, depth;   // CV_32F
  reference::ErrorReport error;
  reference::FrameError frame;
};

// `variant` is the reference's (ao|obscurance|unbounded), `rays` its rays per pixel; the case's
// radius is the reference's too. Throws for an unknown scene, view, technique or variant.
ErrorStudy measure_error_study(const CaseOptions& c, const std::string& variant, int rays);

// `aosuite error --json`: the case, the reference and both errors (`c` and `variant` as given).
nlohmann::ordered_json error_study_json(const ErrorStudy& e, const CaseOptions& c,
                                        const std::string& variant);

}  // namespace aosuite::ao

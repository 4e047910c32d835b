// The perceptual error of the whole frame, not only of the AO term: a technique's final image
// against the same lit scene shaded with the ray-traced AO. Both are shaded here, the same way
// as renderer/passes/shaders/blend.glsl (linear lit colour times AO, sRGB-encoded; sky untouched),
// from the one no-AO image, so the two differ only by their AO.
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string_view>
#include <vector>

#include "compare/metric.hpp"

namespace aosuite::reference {

// no_ao: CV_8UC4 sRGB; ao: CV_32F in [0, 1]; depth: CV_32F, 0 on sky. Returns CV_8UC4.
cv::Mat shade(const cv::Mat& no_ao, const cv::Mat& ao, const cv::Mat& depth);

// Every registered metric's main value (FLIP's mean, SSIM's mean, RMSE, PSNR in dB), keyed by
// the metric's name, in the registry's order.
struct FrameError {
  std::vector<metric::Value> values;
  double value(std::string_view metric) const;  // throws std::out_of_range
};
nlohmann::ordered_json to_json(const FrameError& e);  // {"flip": ..., "ssim": ...}; inf: null
FrameError frame_error_from_json(const nlohmann::json& j);

// The technique's shaded frame (its AO `estimate`) against the reference's. Throws
// std::invalid_argument for images of different sizes or types.
FrameError frame_error(const cv::Mat& no_ao, const cv::Mat& estimate, const cv::Mat& reference,
                       const cv::Mat& depth);

}  // namespace aosuite::reference

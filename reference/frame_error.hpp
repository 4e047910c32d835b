// The perceptual error of the whole frame, not only of the AO term: a technique's final image
// against the same lit scene shaded with the ray-traced AO. Both are shaded here, the same way
// as renderer/shaders/blend.frag (linear lit colour times AO, sRGB-encoded; sky untouched),
// from the one no-AO image, so the two differ only by their AO.
#pragma once

#include <opencv2/core.hpp>

namespace aosuite::reference {

// no_ao: CV_8UC4 sRGB; ao: CV_32F in [0, 1]; depth: CV_32F, 0 on sky. Returns CV_8UC4.
cv::Mat shade(const cv::Mat& no_ao, const cv::Mat& ao, const cv::Mat& depth);

struct FrameError {
  double flip_mean = 0;  // LDR-FLIP (compare/metric.hpp's flip), mean over the frame
  double ssim = 0;       // SSIM over R, G, B (its ssim), as scikit-image computes it
};

// The technique's shaded frame (its AO `estimate`) against the reference's. Throws
// std::invalid_argument for images of different sizes or types.
FrameError frame_error(const cv::Mat& no_ao, const cv::Mat& estimate, const cv::Mat& reference,
                       const cv::Mat& depth);

}  // namespace aosuite::reference

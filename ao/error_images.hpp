// The pictures `aosuite error --out` writes beside the numbers: an AO term as grey, and the
// signed error against the reference as a heat map.
#pragma once

#include <opencv2/core.hpp>

namespace aosuite::ao {

// A CV_32F AO term in [0, 1] as opaque grey CV_8UC4.
cv::Mat grey_rgba(const cv::Mat& ao);

// Signed error, estimate - reference: red where the estimate is too bright, blue where it is
// too dark, full colour at |error| >= 0.25; background (depth <= 0) black.
cv::Mat heat_map(const cv::Mat& estimate, const cv::Mat& reference, const cv::Mat& depth);

}  // namespace aosuite::ao

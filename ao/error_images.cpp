#include "ao/error_images.hpp"

#include <algorithm>
#include <cmath>

namespace aosuite::ao {

cv::Mat grey_rgba(const cv::Mat& ao) {
  cv::Mat out(ao.size(), CV_8UC4);
  for (int y = 0; y < ao.rows; ++y) {
    for (int x = 0; x < ao.cols; ++x) {
      // saturate_cast rounds to nearest itself.
      const auto v = cv::saturate_cast<unsigned char>(ao.at<float>(y, x) * 255.0f);
      out.at<cv::Vec4b>(y, x) = {v, v, v, 255};
    }
  }
  return out;
}

cv::Mat heat_map(const cv::Mat& estimate, const cv::Mat& reference, const cv::Mat& depth) {
  cv::Mat out(estimate.size(), CV_8UC4, cv::Scalar(0, 0, 0, 255));
  for (int y = 0; y < out.rows; ++y) {
    for (int x = 0; x < out.cols; ++x) {
      if (!(depth.at<float>(y, x) > 0)) continue;
      const float e = estimate.at<float>(y, x) - reference.at<float>(y, x);
      const auto s = cv::saturate_cast<unsigned char>(std::min(std::abs(e) / 0.25f, 1.0f) * 255);
      const auto rest = static_cast<unsigned char>(255 - s);
      out.at<cv::Vec4b>(y, x) =
          e > 0 ? cv::Vec4b{255, rest, rest, 255} : cv::Vec4b{rest, rest, 255, 255};
    }
  }
  return out;
}

}  // namespace aosuite::ao

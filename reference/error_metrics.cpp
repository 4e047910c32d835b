#include "reference/error_metrics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "compare/metric.hpp"
#include "compare/ssim.hpp"

namespace aosuite::reference {
namespace {

ErrorStats stats(const cv::Mat& est, const cv::Mat& ref, const cv::Mat& ssim, const cv::Mat& mask,
                 int rays) {
  ErrorStats s;
  double sq = 0, abs = 0, signed_sum = 0, ssim_sum = 0, var = 0;
  for (int y = 0; y < est.rows; ++y) {
    for (int x = 0; x < est.cols; ++x) {
      if (!mask.at<unsigned char>(y, x)) continue;
      const double a = ref.at<float>(y, x), e = est.at<float>(y, x) - a;
      sq += e * e, abs += std::abs(e), signed_sum += e, ssim_sum += ssim.at<float>(y, x);
      var += a * (1 - a);
      ++s.pixels;
    }
  }
  if (s.pixels == 0) return s;
  const double n = static_cast<double>(s.pixels);
  s.rmse = std::sqrt(sq / n), s.mae = abs / n, s.bias = signed_sum / n, s.ssim = ssim_sum / n;
  s.psnr = metric::psnr_db(sq / n);
  s.noise_floor = std::sqrt(std::max(var, 0.0) / n / rays);
  return s;
}

}  // namespace

cv::Mat geometry_mask(const cv::Mat& depth, int border) {
  cv::Mat mask(depth.size(), CV_8U, cv::Scalar(0));
  for (int y = border; y < depth.rows - border; ++y) {
    for (int x = border; x < depth.cols - border; ++x)
      mask.at<unsigned char>(y, x) = depth.at<float>(y, x) > 0 ? 255 : 0;
  }
  return mask;
}

double masked_rmse(const cv::Mat& estimate, const cv::Mat& reference, const cv::Mat& mask) {
  const int n = cv::countNonZero(mask);
  if (n == 0) return 0;
  const double norm = cv::norm(estimate, reference, cv::NORM_L2, mask);
  return norm / std::sqrt(static_cast<double>(n));
}

cv::Mat depth_edge_mask(const cv::Mat& depth, float relative_threshold) {
  cv::Mat mask(depth.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x < depth.cols; ++x) {
      const float z = depth.at<float>(y, x);
      if (!(z > 0)) continue;
      bool edge = false;
      for (int dy = -1; dy <= 1 && !edge; ++dy) {
        for (int dx = -1; dx <= 1 && !edge; ++dx) {
          const int yy = std::clamp(y + dy, 0, depth.rows - 1),
                    xx = std::clamp(x + dx, 0, depth.cols - 1);
          const float n = depth.at<float>(yy, xx);
          edge = !(n > 0) || std::abs(n - z) > relative_threshold * z;
        }
      }
      mask.at<unsigned char>(y, x) = edge ? 255 : 0;
    }
  }
  return mask;
}

cv::Mat ssim_map(const cv::Mat& a, const cv::Mat& b) {
  // The project's one SSIM (compare/ssim.hpp), with this module's conventions: data in
  // [0, 1] and replicated borders (the masks keep pixels away from the border anyway).
  ssim::Options o;
  o.data_range = 1.0;
  o.border = ssim::Border::replicate;
  const cv::Mat ca = a.isContinuous() ? a : a.clone(), cb = b.isContinuous() ? b : b.clone();
  cv::Mat out(a.size(), CV_32F);
  ssim::ssim_map({ca.ptr<float>(), ca.cols, ca.rows, ca.step1(), 1},
                 {cb.ptr<float>(), cb.cols, cb.rows, cb.step1(), 1}, o, out.ptr<float>());
  return out;
}

ErrorReport measure_error(const cv::Mat& estimate, const cv::Mat& reference, const cv::Mat& depth,
                          const MetricOptions& o) {
  if (estimate.type() != CV_32F || reference.type() != CV_32F || depth.type() != CV_32F ||
      estimate.size() != reference.size() || estimate.size() != depth.size()) {
    throw std::invalid_argument(
        "measure_error: estimate, reference and depth must be CV_32F of one size");
  }
  const cv::Mat ssim = ssim_map(estimate, reference);
  const cv::Mat all = geometry_mask(depth, o.border),
                edges = depth_edge_mask(depth, o.edge_threshold);
  cv::Mat edge, interior;
  cv::bitwise_and(all, edges, edge);
  cv::bitwise_and(all, ~edges, interior);
  return {stats(estimate, reference, ssim, all, o.reference_rays),
          stats(estimate, reference, ssim, edge, o.reference_rays),
          stats(estimate, reference, ssim, interior, o.reference_rays)};
}

}  // namespace aosuite::reference

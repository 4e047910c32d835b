// How far a technique's AO term is from the ray-traced reference, on linear visibility in
// [0, 1]: over pixels that are geometry in both (the same G-buffer), away from a border band,
// and split into depth-edge and interior pixels (haloing vs flat-surface self-occlusion).
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>

namespace aosuite::reference {

struct ErrorStats {
  std::size_t pixels = 0;  // all other fields are 0 when there are none
  double rmse = 0, mae = 0;
  double bias = 0;  // mean(estimate - reference): negative = darker than the truth
  double psnr = 0;  // 10 log10(1 / MSE), compare/metric.hpp's psnr_db: +inf when exact
  double ssim = 0;  // mean of the SSIM map over these pixels
  // The reference's own noise, RMS over these pixels: sqrt(mean(A(1-A)) / N), the i.i.d.
  // bound on the estimator's per-pixel spread. RMSE near it is indistinguishable from noise.
  double noise_floor = 0;
};

struct ErrorReport {
  ErrorStats all, edge, interior;
};

struct MetricOptions {
  int border = 8;                // pixels masked at each side (>= SSIM's window radius)
  float edge_threshold = 0.05f;  // a 3x3 neighbour's depth differs by > 5 % (or is sky)
  int reference_rays = 256;      // N, for the noise floor
};

// CV_8U masks (255 = in): geometry (depth > 0) away from the border; depth edges.
cv::Mat geometry_mask(const cv::Mat& depth, int border);
// ErrorStats::rmse alone, over `mask`'s pixels (0 when there are none): what `aosuite tune`
// minimises, measured thousands of times, so without SSIM and the edge masks.
double masked_rmse(const cv::Mat& estimate, const cv::Mat& reference, const cv::Mat& mask);
cv::Mat depth_edge_mask(const cv::Mat& depth, float relative_threshold);

// SSIM map (Wang et al. 2004) with an 11x11 Gaussian window of sigma 1.5 (edges replicated),
// C1 = 0.01^2 and C2 = 0.03^2 for data in [0, 1]; CV_32F. Computed by compare/ssim.hpp (in
// double; the project's one SSIM).
cv::Mat ssim_map(const cv::Mat& a, const cv::Mat& b);

// Throws std::invalid_argument unless estimate, reference and depth are CV_32F of one size.
ErrorReport measure_error(const cv::Mat& estimate, const cv::Mat& reference, const cv::Mat& depth,
                          const MetricOptions& options = {});

}  // namespace aosuite::reference

#include "reference/error_metrics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace aosuite::reference {
namespace {

constexpr int kWindowRadius = 5;  // 11 taps
constexpr double kSigma = 1.5;

std::array<float, 2 * kWindowRadius + 1> gaussian_taps() {
  std::array<float, 2 * kWindowRadius + 1> w{};
  double sum = 0;
  for (int i = -kWindowRadius; i <= kWindowRadius; ++i)
    sum += std::exp(-i * i / (2 * kSigma * kSigma));
  for (int i = -kWindowRadius; i <= kWindowRadius; ++i)
    w[i + kWindowRadius] = static_cast<float>(std::exp(-i * i / (2 * kSigma * kSigma)) / sum);
  return w;
}

// Separable Gaussian with replicated edges (only OpenCV core is linked, not imgproc).
cv::Mat gaussian_blur(const cv::Mat& in) {
  static const auto taps = gaussian_taps();
  const int w = in.cols, h = in.rows;
  cv::Mat across(in.size(), CV_32F), out(in.size(), CV_32F);
  for (int y = 0; y < h; ++y) {
    const float* src = in.ptr<float>(y);
    float* dst = across.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      float s = 0;
      for (int k = -kWindowRadius; k <= kWindowRadius; ++k)
        s += taps[k + kWindowRadius] * src[std::clamp(x + k, 0, w - 1)];
      dst[x] = s;
    }
  }
  for (int y = 0; y < h; ++y) {
    float* dst = out.ptr<float>(y);
    std::fill(dst, dst + w, 0.0f);
    for (int k = -kWindowRadius; k <= kWindowRadius; ++k) {
      const float* src = across.ptr<float>(std::clamp(y + k, 0, h - 1));
      for (int x = 0; x < w; ++x) dst[x] += taps[k + kWindowRadius] * src[x];
    }
  }
  return out;
}

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
  s.psnr = 10 * std::log10(1 / std::max(sq / n, 1e-10));
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
  constexpr float c1 = 0.01f * 0.01f, c2 = 0.03f * 0.03f;
  const cv::Mat mu_a = gaussian_blur(a), mu_b = gaussian_blur(b);
  const cv::Mat aa = gaussian_blur(a.mul(a)), bb = gaussian_blur(b.mul(b)),
                ab = gaussian_blur(a.mul(b));
  cv::Mat out(a.size(), CV_32F);
  for (int y = 0; y < a.rows; ++y) {
    for (int x = 0; x < a.cols; ++x) {
      const float ma = mu_a.at<float>(y, x), mb = mu_b.at<float>(y, x);
      const float va = aa.at<float>(y, x) - ma * ma, vb = bb.at<float>(y, x) - mb * mb,
                  cov = ab.at<float>(y, x) - ma * mb;
      out.at<float>(y, x) =
          ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
    }
  }
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

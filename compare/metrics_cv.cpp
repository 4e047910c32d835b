#include "compare/metrics_cv.hpp"

#include <stdexcept>
#include <vector>

#include "compare/opencv.hpp"

namespace aosuite {

flip::RgbFloatView rgb_float_view(const cv::Mat& rgb) {
  if (rgb.type() != CV_32FC3) throw std::invalid_argument("expected a CV_32FC3 image");
  return {rgb.ptr<float>(), rgb.cols, rgb.rows, rgb.step1()};
}

namespace flip {
FlipResult compare(const cv::Mat& reference, const cv::Mat& test, bool hdr,
                   const Options& options) {
  if (reference.type() == CV_8UC4 && test.type() == CV_8UC4 && !hdr) {
    const cv::Mat a = reference.isContinuous() ? reference : reference.clone();
    const cv::Mat b = test.isContinuous() ? test : test.clone();
    return compare_ldr(view_of(a), view_of(b), options);
  }
  const auto r = rgb_float_view(reference), t = rgb_float_view(test);
  return hdr ? compare_hdr(r, t, options) : compare_ldr_linear(r, t, options);
}
}  // namespace flip

namespace ssim {
SsimResult compare(const cv::Mat& a, const cv::Mat& b, const Options& options) {
  if (a.type() != b.type() || a.size() != b.size())
    throw std::invalid_argument("ssim: images differ in type or size");
  if (a.type() == CV_8UC4) {
    const cv::Mat ca = a.isContinuous() ? a : a.clone();
    const cv::Mat cb = b.isContinuous() ? b : b.clone();
    return compare_rgb(view_of(ca), view_of(cb), options);
  }
  if (a.type() == CV_8UC1)
    return compare(Plane<std::uint8_t>{a.ptr<std::uint8_t>(), a.cols, a.rows, a.step1(), 1},
                   Plane<std::uint8_t>{b.ptr<std::uint8_t>(), b.cols, b.rows, b.step1(), 1},
                   options);
  if (a.depth() == CV_32F && (a.channels() == 1 || a.channels() == 3)) {
    const auto n = std::size_t(a.channels());
    return compare_channels(Plane<float>{a.ptr<float>(), a.cols, a.rows, a.step1(), n},
                            Plane<float>{b.ptr<float>(), b.cols, b.rows, b.step1(), n},
                            a.channels(), options);
  }
  throw std::invalid_argument("ssim: expected CV_8UC4, CV_8UC1, CV_32FC1 or CV_32FC3 images");
}
}  // namespace ssim

}  // namespace aosuite

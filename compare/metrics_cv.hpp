// FLIP and SSIM for cv::Mat images: CV_8UC4 RGBA (sRGB), CV_32FC3 linear RGB in R, G, B
// order (as OpenImageIO reads EXR), CV_8UC1 and CV_32FC1 planes.
#pragma once

#include <opencv2/core.hpp>

#include "compare/flip.hpp"
#include "compare/ssim.hpp"

namespace aosuite {

// A view of a CV_32FC3 mat (throws std::invalid_argument for any other type).
flip::RgbFloatView rgb_float_view(const cv::Mat& rgb);

namespace flip {
// CV_8UC4 sRGB -> compare_ldr; CV_32FC3 -> compare_ldr_linear (hdr = false) or compare_hdr.
FlipResult compare(const cv::Mat& reference, const cv::Mat& test, bool hdr,
                   const Options& options = {});
}  // namespace flip

namespace ssim {
// CV_8UC4: R, G, B with data_range 255 unless given; CV_8UC1; CV_32FC1 and CV_32FC3 (the mean
// of the channels' SSIM) with options.data_range as given.
SsimResult compare(const cv::Mat& a, const cv::Mat& b, const Options& options = {});
}  // namespace ssim

}  // namespace aosuite

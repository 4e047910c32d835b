// The comparator for code that holds its images as cv::Mat (the renderer, the harness,
// tests): CV_8UC4 RGBA mats are viewed without copying. `aosuite compare` itself never
// links this, so its start-up does not pay for loading OpenCV.
#pragma once

#include <filesystem>
#include <opencv2/core.hpp>
#include <span>
#include <string>
#include <vector>

#include "compare/resemble.hpp"
#include "image/image_io.hpp"
#include "image/picture.hpp"

namespace aosuite {

// A continuous CV_8UC4 mat as a view (throws cv::Exception for any other kind).
RgbaView view_of(const cv::Mat& rgba);
cv::Mat to_mat(RgbaView rgba);  // a CV_8UC4 copy; an empty mat for an empty view
// A continuous CV_8UC4 mat as an 8-bit Picture for the metrics (a copy of its pixels).
Picture picture_of(const cv::Mat& rgba, std::string name);

cv::Mat decode_png_rgba8(std::span<const unsigned char> png, const std::string& name);
cv::Mat read_png_rgba8(const std::filesystem::path& path);
std::vector<unsigned char> encode_png_rgba8(const cv::Mat& rgba, int compression_level);
void write_png_rgba8(const std::filesystem::path& path, const cv::Mat& rgba,
                     int compression_level = 3);

namespace resemble {
Result compare(const cv::Mat& a, const cv::Mat& b, const Options& options);
}  // namespace resemble

}  // namespace aosuite

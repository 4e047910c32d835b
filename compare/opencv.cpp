#include "compare/opencv.hpp"

#include <cstring>

namespace aosuite {

RgbaView view_of(const cv::Mat& rgba) {
  if (rgba.empty()) return {};
  CV_Assert(rgba.type() == CV_8UC4 && rgba.isContinuous());
  return {rgba.data, rgba.cols, rgba.rows};
}

Picture picture_of(const cv::Mat& rgba, std::string name) {
  Picture p;
  p.name = std::move(name);
  p.rgba = copy_of(view_of(rgba));
  return p;
}

cv::Mat to_mat(RgbaView rgba) {
  if (rgba.bytes() == 0) return {};
  cv::Mat m(rgba.height, rgba.width, CV_8UC4);
  std::memcpy(m.data, rgba.data, rgba.bytes());
  return m;
}

cv::Mat decode_png_rgba8(std::span<const unsigned char> png, const std::string& name) {
  return to_mat(decode_png(png, name));
}

cv::Mat read_png_rgba8(const std::filesystem::path& path) { return to_mat(read_png(path)); }

std::vector<unsigned char> encode_png_rgba8(const cv::Mat& rgba, int compression_level) {
  return encode_png_rgba8(view_of(rgba), compression_level);
}

void write_png_rgba8(const std::filesystem::path& path, const cv::Mat& rgba,
                     int compression_level) {
  write_png_rgba8(path, view_of(rgba), compression_level);
}

namespace resemble {
Result compare(const cv::Mat& a, const cv::Mat& b, const Options& options) {
  // A non-continuous mat (a region of a larger one) is copied once so it can be viewed.
  const cv::Mat ca = a.isContinuous() ? a : a.clone(), cb = b.isContinuous() ? b : b.clone();
  return compare(view_of(ca), view_of(cb), options);
}
}  // namespace resemble

}  // namespace aosuite

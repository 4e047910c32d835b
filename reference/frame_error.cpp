#include "reference/frame_error.hpp"

#include <cmath>
#include <stdexcept>

#include "compare/metric.hpp"
#include "compare/opencv.hpp"
#include "compare/srgb.hpp"

namespace aosuite::reference {
namespace {

// blend.glsl's to_srgb, then 8 bits as the GL read-back rounds them.
unsigned char to_srgb8(float c) {
  return static_cast<unsigned char>(std::lround(linear_to_srgb(c) * 255.0f));
}

}  // namespace

cv::Mat shade(const cv::Mat& no_ao, const cv::Mat& ao, const cv::Mat& depth) {
  if (no_ao.type() != CV_8UC4 || ao.type() != CV_32F || depth.type() != CV_32F ||
      no_ao.size() != ao.size() || ao.size() != depth.size()) {
    throw std::invalid_argument("shade: expected CV_8UC4, CV_32F and CV_32F images of one size");
  }
  cv::Mat out = no_ao.clone();
  for (int y = 0; y < out.rows; ++y) {
    for (int x = 0; x < out.cols; ++x) {
      if (!(depth.at<float>(y, x) > 0)) continue;  // sky: no AO
      const float a = std::clamp(ao.at<float>(y, x), 0.0f, 1.0f);
      cv::Vec4b& p = out.at<cv::Vec4b>(y, x);
      for (int c = 0; c < 3; ++c) p[c] = to_srgb8(srgb_to_linear(float(p[c]) / 255.0f) * a);
    }
  }
  return out;
}

FrameError frame_error(const cv::Mat& no_ao, const cv::Mat& estimate, const cv::Mat& reference,
                       const cv::Mat& depth) {
  const Picture truth = picture_of(shade(no_ao, reference, depth), "reference frame");
  const Picture test = picture_of(shade(no_ao, estimate, depth), "technique frame");
  FrameError e;
  for (const metric::Metric* m : metric::all()) {
    e.values.push_back({std::string(m->name), metric::measure(*m, truth, test).value(m->primary)});
  }
  return e;
}

double FrameError::value(std::string_view metric) const {
  for (const metric::Value& v : values)
    if (v.key == metric) return v.value;
  throw std::out_of_range("no frame error for " + std::string(metric));
}

nlohmann::ordered_json to_json(const FrameError& e) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (const metric::Value& v : e.values)
    j[v.key] = std::isfinite(v.value) ? nlohmann::ordered_json(v.value) : nullptr;
  return j;
}

FrameError frame_error_from_json(const nlohmann::json& j) {
  FrameError e;
  for (const metric::Metric* m : metric::all()) {
    const nlohmann::json& v = j.at(std::string(m->name));
    e.values.push_back({std::string(m->name), v.is_null() ? HUGE_VAL : v.get<double>()});
  }
  return e;
}

}  // namespace aosuite::reference

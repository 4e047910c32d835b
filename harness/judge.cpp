#include "harness/judge.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "compare/opencv.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

std::string_view status_name(Status s) {
  switch (s) {
    case Status::kPass:
      return "PASS";
    case Status::kFail:
      return "FAIL";
    case Status::kNew:
      return "NEW";
    case Status::kError:
      return "ERROR";
    case Status::kFlaky:
      return "FLAKY";
  }
  return "ERROR";
}

Status parse_status(std::string_view name) {
  for (Status s : {Status::kPass, Status::kFail, Status::kNew, Status::kError, Status::kFlaky}) {
    if (status_name(s) == name) return s;
  }
  throw std::invalid_argument("unknown status '" + std::string(name) + "'");
}

namespace {

// The render with ignored regions taken from the golden, so neither Resemble nor the channel
// delta sees a difference there.
cv::Mat without_ignored(const cv::Mat& render, const cv::Mat& golden, const Tolerance& t) {
  if (t.ignore.empty() && t.mask.empty()) return render;
  cv::Mat out = render.clone();
  const cv::Rect frame(0, 0, render.cols, render.rows);
  for (const resemble::Box& b : t.ignore) {
    const cv::Rect r =
        cv::Rect(cv::Point(static_cast<int>(b.left), static_cast<int>(b.top)),
                 cv::Point(static_cast<int>(b.right) + 1, static_cast<int>(b.bottom) + 1)) &
        frame;
    golden(r).copyTo(out(r));
  }
  if (!t.mask.empty()) {
    const cv::Mat mask = read_png_rgba8(t.mask);
    if (mask.size() != render.size()) {
      throw std::runtime_error(fmt::format("mask {} is {}x{}, the images are {}x{}",
                                           t.mask.string(), mask.cols, mask.rows, render.cols,
                                           render.rows));
    }
    for (int y = 0; y < mask.rows; ++y) {
      for (int x = 0; x < mask.cols; ++x) {
        const cv::Vec4b m = mask.at<cv::Vec4b>(y, x);
        if (m[0] != 0 || m[1] != 0 || m[2] != 0)
          out.at<cv::Vec4b>(y, x) = golden.at<cv::Vec4b>(y, x);
      }
    }
  }
  return out;
}

int max_channel_delta(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat d;
  cv::absdiff(a, b, d);
  double hi = 0;
  cv::minMaxLoc(d.reshape(1), nullptr, &hi);
  return static_cast<int>(hi);
}

resemble::Options resemble_options(const Tolerance& t, bool diff) {
  resemble::Options o;
  o.modes = {t.mode};
  o.produce_diff = diff;
  return o;
}

// One golden against the render; kError when the golden cannot be read.
ImageVerdict against(std::string_view image, std::span<const unsigned char> render_png,
                     const cv::Mat& render, const fs::path& golden_file, const Tolerance& t) {
  ImageVerdict v;
  v.image = std::string(image), v.golden = golden_file;
  try {
    const std::vector<unsigned char> bytes = read_file(golden_file);
    if (std::equal(bytes.begin(), bytes.end(), render_png.begin(), render_png.end())) {
      v.status = Status::kPass, v.identical = true, v.mismatch_text = "0.00";
      return v;
    }
    const cv::Mat golden = decode_png_rgba8(bytes, golden_file.string());
    if (golden.size() != render.size()) {
      v.status = Status::kFail, v.mismatch_percent = 100, v.mismatch_text = "100.00";
      v.message = fmt::format("golden is {}x{}, render is {}x{}", golden.cols, golden.rows,
                              render.cols, render.rows);
      return v;
    }
    const cv::Mat judged = without_ignored(render, golden, t);
    const resemble::Result r = resemble::compare(golden, judged, resemble_options(t, false));
    v.mismatch_percent = r.raw_mismatch_percentage;
    v.mismatch_text = r.mismatch_percentage;
    v.max_channel_delta = max_channel_delta(golden, judged);
    const bool within =
        v.mismatch_percent <= t.max_mismatch_percent && v.max_channel_delta <= t.max_channel_delta;
    v.status = within ? Status::kPass : Status::kFail;
    if (!within) {
      v.message =
          fmt::format("mismatch {}% (allowed {}%)", v.mismatch_text, t.max_mismatch_percent);
      if (t.max_channel_delta < 255) {
        v.message += fmt::format(", max channel delta {} (allowed {})", v.max_channel_delta,
                                 t.max_channel_delta);
      }
    }
  } catch (const std::exception& e) {
    v.status = Status::kError;
    v.message = e.what();
  }
  return v;
}

}  // namespace

ImageVerdict judge(std::string_view image, std::span<const unsigned char> render_png,
                   const cv::Mat& render, const std::vector<fs::path>& goldens,
                   const Tolerance& tolerance, bool want_diff) {
  if (goldens.empty()) {
    ImageVerdict v;
    v.image = std::string(image), v.status = Status::kNew, v.message = "no golden yet";
    return v;
  }
  // Every accepted golden is read, even after one passes: a damaged golden or variant is an
  // error to repair, not something another variant may hide.
  std::vector<ImageVerdict> tried;
  for (const fs::path& g : goldens)
    tried.push_back(against(image, render_png, render, g, tolerance));
  for (const ImageVerdict& v : tried) {
    if (v.status == Status::kError) return v;
  }
  for (const ImageVerdict& v : tried) {
    if (v.status == Status::kPass) return v;
  }
  // None passed: report the closest golden.
  ImageVerdict best = *std::min_element(tried.begin(), tried.end(), [](auto& a, auto& b) {
    return a.mismatch_percent < b.mismatch_percent;
  });
  if (want_diff && best.status == Status::kFail && best.mismatch_percent < 100) {
    const cv::Mat golden = read_png_rgba8(best.golden);
    best.diff = resemble::compare(golden, without_ignored(render, golden, tolerance),
                                  resemble_options(tolerance, true))
                    .diff;
  }
  return best;
}

}  // namespace aosuite::harness

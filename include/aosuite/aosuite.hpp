// aosuite as a C++ library (find_package(aosuite), target aosuite::aosuite): judge a renderer's
// image against a golden exactly as `aosuite compare`, folder mode and `aosuite check` do (one
// comparison, one tolerance, the same defaults), from the renderer's own tests, in memory.
// Standard C++ only: no OpenCV, GL or Embree types.
//
//   aosuite::Image frame = render_my_frame();  // 8-bit RGBA, rows top to bottom
//   EXPECT_TRUE(aosuite::matches_golden(frame, "goldens/frame.png"));
//
// On a failure the actual image and the diff are written under
// $AOSUITE_FAILURES (default: `aosuite-failures` in the current directory), and the verdict's
// message gives their paths. With AOSUITE_UPDATE_GOLDENS=1 a missing or failing golden is
// written from the image, in the golden file's own format (.png or .exr).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#define AOSUITE_API __attribute__((visibility("default")))

namespace aosuite {

// 8-bit RGBA pixels, rows top to bottom, width * height * 4 bytes.
struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;
};

// Linear float samples (an HDR frame, an AO term), rows top to bottom, 1 (grey) or 3 (R, G, B)
// interleaved channels: width * height * channels floats. Goldens are EXR files.
struct FloatFrame {
  int width = 0, height = 0, channels = 1;
  std::vector<float> samples;
};

// When two images count as the same: the CLI's tolerance, field for field, with its defaults
// (docs/compare.md, "The one rule"). Every limit holds unless a field changes it; setting one
// leaves every other in force, and lifting one takes an explicit value (max_channel_delta =
// 255).
struct Tolerance {
  std::string mode = "less";  // Resemble.js's: nothing, less, antialiasing, colors, alpha
  double max_mismatch_percent = 0;
  int max_channel_delta = 8;       // largest |actual - expected| of any channel
  double max_mean_shift = 0.5;     // largest |mean difference| of any channel, in levels
  double max_mean_delta = 0.25;    // mean |difference| of every sample, in levels
  int shift_radius = 0;            // forgive a differing pixel matched within this many pixels
  bool allow_kind_change = false;  // another bit depth or channel layout fails unless true
  bool resemble = true;            // false lifts Resemble's gate and the channel limits above
  // "METRIC.KEY=VALUE" as `aosuite compare --gate`: "flip.max_mean=0.02", "rmse.max=0.01";
  // beside the limits above, for every image. float_gates: for float images only (without
  // any gate, float images must be byte-identical).
  std::vector<std::string> gates, float_gates;
};

struct Verdict {
  enum class Status { kPass, kFail, kNew, kError };
  Status status = Status::kError;
  double mismatch_percent = 0;  // Resemble.js's rawMisMatchPercentage
  int max_channel_delta = 0;
  double mean_shift = 0, mean_delta = 0;
  // Why it failed, is new or could not be judged, with the failure images' and the golden's
  // paths; "" when it passed.
  std::string message;
  std::string actual_file, diff_file;  // failure images written (matches_golden), or ""
  explicit operator bool() const { return status == Status::kPass; }
};
AOSUITE_API std::ostream& operator<<(std::ostream& out, const Verdict& v);

// Any image file aosuite reads (PNG, EXR, JPEG, TIFF, WebP, HDR, TGA, BMP) as 8-bit RGBA, as a
// browser's canvas would hold it. Throws std::runtime_error naming the file and the problem.
AOSUITE_API Image read_image(const std::string& file);
// A float file (EXR, HDR, float TIFF) as linear samples, one or three channels.
AOSUITE_API FloatFrame read_float_image(const std::string& file);
// Writes `image` as a PNG (an EXR), replacing the file only once it is complete.
AOSUITE_API void write_png(const std::string& file, const Image& image);
AOSUITE_API void write_exr(const std::string& file, const FloatFrame& image);

// `actual` against `expected` under `tolerance`, in memory.
AOSUITE_API Verdict compare(const Image& actual, const Image& expected,
                            const Tolerance& tolerance = {});
AOSUITE_API Verdict compare(const FloatFrame& actual, const FloatFrame& expected,
                            const Tolerance& tolerance = {});
// `image` against the golden file: kNew when there is none yet, naming its path and the
// variable that writes it. `test_name` names the folder of the failure images (default: the
// golden's stem).
AOSUITE_API Verdict matches_golden(const Image& image, const std::string& golden,
                                   const Tolerance& tolerance = {},
                                   const std::string& test_name = "");
AOSUITE_API Verdict matches_golden(const FloatFrame& image, const std::string& golden,
                                   const Tolerance& tolerance = {},
                                   const std::string& test_name = "");

}  // namespace aosuite

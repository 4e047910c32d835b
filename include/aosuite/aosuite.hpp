// aosuite as a C++ library (find_package(aosuite), target aosuite::aosuite): judge a renderer's
// image against a golden the way `aosuite compare` and `aosuite check` do, from the renderer's
// own tests. Standard C++ only: no OpenCV, GL or Embree types.
//
//   aosuite::Image frame = render_my_frame();  // 8-bit RGBA, rows top to bottom
//   EXPECT_TRUE(aosuite::matches_golden(frame, "goldens/frame.png", {.max_mismatch_percent =
//   0.1}));
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

// When two images count as the same. Resemble.js's gate (its `mode`, the mismatch percentage
// allowed, the largest channel difference allowed) and/or metric gates, all of which must hold.
struct Tolerance {
  std::string mode = "nothing";  // nothing, less, antialiasing, colors, alpha (Resemble.js)
  double max_mismatch_percent = 0;
  int max_channel_delta = 255;
  // "METRIC.KEY=VALUE" as `aosuite compare --gate`: "flip.max_mean=0.02", "rmse.max=0.01".
  // Given alone, they replace Resemble's gate (set resemble = true to keep both).
  std::vector<std::string> gates;
  bool resemble = false;
};

struct Verdict {
  enum class Status { kPass, kFail, kNew, kError };
  Status status = Status::kError;
  double mismatch_percent = 0;  // Resemble.js's rawMisMatchPercentage
  int max_channel_delta = 0;
  std::string message;  // why it failed, is new or could not be judged; "" when it passed
  explicit operator bool() const { return status == Status::kPass; }
};
AOSUITE_API std::ostream& operator<<(std::ostream& out, const Verdict& v);

// Any image file aosuite reads (PNG, EXR, JPEG, TIFF, WebP, HDR, TGA, BMP) as 8-bit RGBA, as a
// browser's canvas would hold it. Throws std::runtime_error naming the file and the problem.
AOSUITE_API Image read_image(const std::string& file);
// Writes `image` as a PNG, replacing the file only once it is complete.
AOSUITE_API void write_png(const std::string& file, const Image& image);

// `actual` against `expected` under `tolerance`.
AOSUITE_API Verdict compare(const Image& actual, const Image& expected,
                            const Tolerance& tolerance = {});
// `image` against the golden file: kNew when there is none yet (with AOSUITE_UPDATE_GOLDENS=1
// in the environment, a missing or failing golden is written from `image` and the verdict
// passes, saying so).
AOSUITE_API Verdict matches_golden(const Image& image, const std::string& golden,
                                   const Tolerance& tolerance = {});

}  // namespace aosuite

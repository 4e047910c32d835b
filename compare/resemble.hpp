// Resemble.js 5.0.0's image comparison, reproduced exactly (docs/compare.md): same verdict per
// pixel, same mismatch percentage bit for bit, same bounds, same diff image bytes, checked
// against the library itself by tests/oracle_differential_test.cpp.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "compare/canvas_alpha.hpp"
#include "compare/count_kernel.hpp"
#include "image/rgba_image.hpp"

namespace aosuite::resemble {

// Resemble's `ignore` modes. kDefault is "no ignore set": the tolerances of kLess, and a
// custom tolerance is then ignored, as in Resemble.
enum class Mode { kDefault, kNothing, kLess, kColors, kAntialiasing, kAlpha };
Mode parse_mode(std::string_view name);  // throws std::invalid_argument
std::string_view mode_name(Mode mode);

enum class ErrorType {
  kFlat,
  kMovement,
  kFlatDifferenceIntensity,
  kMovementDifferenceIntensity,
  kDiffOnly
};
// Unknown names give kFlat, as Resemble silently keeps its default.
ErrorType parse_error_type(std::string_view name);

struct Tolerance {
  double red = 16, green = 16, blue = 16, alpha = 16, min_brightness = 16, max_brightness = 240;
};
// Resemble's `tolerance` option: each field present replaces the mode's value.
struct ToleranceOverride {
  std::optional<double> red, green, blue, alpha, min_brightness, max_brightness;
};

struct Color {
  double r = 255, g = 0, b = 255, a = 255;
};

// A rectangle in Resemble's strict sense: x > left && x < right && y > top && y < bottom.
// right == 0 and bottom == 0 mean the image's width and height.
struct Box {
  double left = 0, top = 0, right = 0, bottom = 0;
};

struct Options {
  std::vector<Mode> modes;  // applied in order, the last wins; empty = Resemble's defaults
  ToleranceOverride tolerance;
  double large_image_threshold = 1200;  // 0 disables; only acts in antialiasing mode
  ErrorType error_type = ErrorType::kFlat;
  Color error_color;
  double transparency = 1;
  std::optional<std::vector<Box>> bounding_boxes;
  std::optional<std::vector<Box>> ignored_boxes;
  std::optional<Color> ignore_areas_colored_with;  // r, g, b compared; overrides the boxes
  double return_early_threshold = 0;               // non-zero: no diff image, stop once above it
  CanvasAlpha canvas_alpha = CanvasAlpha::kNone;
  bool produce_diff = false;
};

// The tolerances and switches the modes resolve to.
struct Settings {
  Tolerance tolerance;
  bool ignore_antialiasing = false;
  bool ignore_colors = false;
};
Settings resolve(const Options& options);

struct Bounds {
  int top = 0, left = 0, bottom = 0, right = 0;
  bool operator==(const Bounds&) const = default;
};

struct Result {
  std::string mismatch_percentage;  // toFixed(2), as Resemble's misMatchPercentage
  double raw_mismatch_percentage = 0;
  std::uint64_t mismatch_count = 0;
  bool same_dimensions = true;
  int width_difference = 0;  // image 1 minus image 2
  int height_difference = 0;
  Bounds diff_bounds;
  double analysis_ms = 0;
  RgbaImage diff;  // when asked for and no early return
};

// a and b as decoded from the files (the canvas model in options decides what a browser
// would have made of translucent pixels).
Result compare(RgbaView a, RgbaView b, const Options& options);

// The bytes compare() allocates for images of sizes a and b beyond the images themselves
// (canvas-model copies, padding to a common size, the diff image, the early-return mask):
// what a memory budget must allow before anything is decoded.
std::uint64_t working_bytes(ImageSize a, ImageSize b, const Options& options);

// The per-channel differences at which a pixel mismatches when these thresholds alone decide
// (no antialiasing or colours mode, no areas, no diff image, no early return): then a
// comparison of the images as seen (after the canvas model) is count_mismatches() and
// result_from_tally(); else nullopt.
std::optional<std::array<int, 4>> count_only_thresholds(const Options& options);

// The result of a comparison of images of sizes a and b with these mismatches, timed from
// `start`. No diff image.
Result result_from_tally(const MismatchTally& tally, ImageSize a, ImageSize b,
                         std::chrono::steady_clock::time_point start);

// What compare(x, x, options) returns for every image x of this size, without reading it:
// an image never differs from itself, whatever the modes, tolerances, areas or canvas model
// (every predicate accepts equal values). No diff image.
Result compare_identical(ImageSize size);

}  // namespace aosuite::resemble

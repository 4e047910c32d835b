// FLIP (Andersson et al., HPG 2020) and HDR-FLIP (EGSR 2021), as NVlabs/flip v1.6's C++ tool
// computes and pools them: the same colour pipeline (sRGB -> linear -> YCxCz, contrast
// sensitivity filters, linear RGB clamp, CIELab + Hunt, HyAB), the same edge/point feature
// filters, the same constants and filter radii; HDR: exposure bracketing with the same
// tone mappers and automatic start/stop exposures, max over exposures.
//
// Kernels only: images come in as views, results go out as one FlipResult. No file I/O.
// Ties to the tool are tested differentially (tests/metric_oracle_test.cpp).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "image/rgba_image.hpp"

namespace aosuite::flip {

// The tool's default: a 0.7 m wide 3840-pixel monitor viewed from 0.7 m, 67.0206 pixels per
// degree (FLIP::calculatePPD(0.7f, 3840.0f, 0.7f), evaluated in float as the tool does).
float pixels_per_degree(float distance_m, float resolution_x, float monitor_width_m);
float default_ppd();

enum class ToneMapper { aces, reinhard, hable };

struct Options {
  float ppd = default_ppd();
  // HDR only. Unset: computed from the reference as the tool does (start from its maximum
  // luminance, stop from its median); num_exposures unset: max(2, ceil(stop - start)).
  ToneMapper tone_mapper = ToneMapper::aces;
  std::optional<float> start_exposure, stop_exposure;
  std::optional<int> num_exposures;
  // The tool's own arithmetic, for its numbers to the bit: glibc's powf for the cube root and
  // the two powers of each pixel's error, where the fast path uses vector approximations within
  // a few ulp of it; and pooling in float as the tool does (its mean one chain of float
  // additions in row order, its weighted percentiles a float running sum over the sorted map).
  // Off by default: the chains drift (at 3840x2160, ~1e-4 on the mean and ~5e-4 on the
  // weighted quartiles), the exact values need no sort of the whole map, and the scalar powers
  // are slower.
  bool tool_arithmetic = false;
};

// Linear-light RGB floats, 3 per pixel, rows `stride` floats apart (>= 3 * width). What a
// CV_32FC3 mat holds in R, G, B order (compare/metrics_cv.hpp takes the mats).
struct RgbFloatView {
  const float* data = nullptr;
  int width = 0, height = 0;
  std::size_t stride = 0;
  const float* row(int y) const { return data + std::size_t(y) * stride; }
};

// The tool's pooled values over the error map (tool/pooling.h): the mean, the weighted
// median and quartiles (the smallest error e, in sorted order, at which the running sum of
// errors exceeds p times their total; 0 when all are 0), min and max. Differences from the
// tool: sums are exact (double) unless Options::tool_arithmetic, and max of an all-zero
// map is 0 (the tool reports FLT_MIN).
struct FlipResult {
  int width = 0, height = 0;
  double mean = 0;
  float weighted_median = 0, first_weighted_quartile = 0, third_weighted_quartile = 0;
  float min = 0, max = 0;
  // HDR only (0 for LDR): the exposures used, computed or given.
  float start_exposure = 0, stop_exposure = 0;
  int num_exposures = 0;
  std::vector<float> error_map;  // width * height values in [0, 1], row-major
};

// Recomputes the pooled values (mean, weighted median and quartiles, min, max) from
// r.error_map as it now is: after keeping only some pixels' errors, say.
void pool(FlipResult& r, bool tool_float_pooling = false);

// LDR-FLIP of two sRGB 8-bit images of one size (alpha is ignored, as the tool's stb_image
// load with 3 channels ignores it). Throws std::invalid_argument for different sizes.
FlipResult compare_ldr(RgbaView reference, RgbaView test, const Options& options = {});

// LDR-FLIP of linear RGB images in [0, 1] (values outside are clamped, as the tool does).
FlipResult compare_ldr_linear(RgbFloatView reference, RgbFloatView test,
                              const Options& options = {});

// HDR-FLIP of linear RGB images (any finite values; NaN counts as 0 and +-inf as
// +-FLT_MAX). When the reference has no positive luminance, or the exposures cannot be
// computed, start = stop = 0 (the tool divides by zero there).
FlipResult compare_hdr(RgbFloatView reference, RgbFloatView test, const Options& options = {});

// The error map as an image, as the tool writes it: magma (index int(e * 255 + 0.5)) or grey
// (byte int(255 e + 0.5)); opaque RGBA8.
enum class ErrorMapStyle { magma, grey };
RgbaImage error_map_image(const FlipResult& result, ErrorMapStyle style = ErrorMapStyle::magma);

}  // namespace aosuite::flip

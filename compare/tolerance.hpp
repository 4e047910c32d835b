// How far an image may stray from the one it is compared with and still count as the same: the
// one tolerance of `aosuite compare`, folder mode, suites, `tolerances suggest`, the report and
// the C++ API. Its defaults are the rule everywhere (docs/compare.md, "The one rule"): every
// limit below holds unless a flag, key or field names it, and naming one limit leaves every
// other in force. Lifting a limit takes an explicit value (max_channel_delta = 255).
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "compare/metric.hpp"
#include "compare/resemble.hpp"

namespace aosuite::comparison {

// A tolerance class of a region map: the golden's <image>.regions.png beside it paints each
// pixel with a class's colour (black: no class); the class's metric gates hold over its pixels,
// and the tolerance's own metric gates over the unpainted ones.
struct Region {
  std::string name;
  std::array<int, 3> color{};  // R, G, B, not all 0
  std::vector<metric::Gates> gates;
};

// The defaults (see each field): what catches a real change and lets a benign one pass, as
// measured on tests/data/corpus (tests/corpus_test.cpp): a 2 % brighter frame, 1 % noise, a
// 1 px shift, a blur, a patch, a channel swap and 16 -> 8 bits fail; a PNG re-encoded, as
// lossless WebP or TIFF, and +-1 on a few pixels pass.
inline constexpr int kDefaultChannelDelta = 8;
inline constexpr double kDefaultMeanShift = 0.5;
inline constexpr double kDefaultMeanDelta = 0.25;

// The warning tier, `[tolerance.warn]` (idiff's -warn beside -fail): tighter limits that a
// passing image may exceed and still pass, with a WARN status that exits 0, so a drift is seen
// before it fails. Only the limits it names are checked; its metric gates judge the whole image
// (with regions, the unpainted pixels), under the tolerance's Resemble mode.
struct WarnLimits {
  double max_mismatch_percent = 100;  // 100, 255, -1: not checked
  int max_channel_delta = 255;
  long long max_differing_pixels = -1;
  std::vector<metric::Gates> gates;
  bool resemble() const {
    return max_mismatch_percent < 100 || max_channel_delta < 255 || max_differing_pixels >= 0;
  }
  bool empty() const { return !resemble() && gates.empty(); }
};

struct Tolerance {
  // Resemble's gate and the channel limits below hold for 8-bit images (16-bit ones as a
  // canvas holds them); `resemble = false` lifts them all, leaving the metric gates alone.
  bool resemble = true;
  resemble::Mode mode = resemble::Mode::kLess;  // any Resemble.js mode
  double max_mismatch_percent = 0;              // Resemble's rawMisMatchPercentage, inclusive
  // Largest |actual - expected| of any RGBA channel: `less` alone ignores up to 16 levels.
  int max_channel_delta = kDefaultChannelDelta;
  // Two-sided budgets (Mozilla's reftest fuzzy(min-max)): `channel_delta = [min, max]`,
  // `differing_pixels = [min, max]` or `max_differing_pixels = N`.
  int min_channel_delta = 0;
  long long min_differing_pixels = 0, max_differing_pixels = -1;  // -1: any
  // The largest |mean of actual - expected| of any channel, in levels: a global shift of
  // brightness or colour that no single pixel shows.
  double max_mean_shift = kDefaultMeanShift;
  // The mean |actual - expected| of every sample, in levels: noise that shifts nothing.
  double max_mean_delta = kDefaultMeanDelta;
  // Filament's shiftRadius: a pixel that differs is forgiven when some expected pixel within
  // this many pixels (a square) is within the channel limit of it (rasterisation jitter).
  int shift_radius = 0;
  // Another bit depth or channel layout (8 against 16 bits, grey against colour, float against
  // 8-bit) fails even where the pixels agree; true accepts it.
  bool allow_kind_change = false;

  std::vector<metric::Gates> gates;  // e.g. flip = { max_mean = 0.02 }: beside the above
  // Gates only for float images (EXR, HDR, float TIFF, 16-bit PNG at full precision), which
  // have no Resemble gate: folder mode's --float-gate, a suite's `[tolerance.float]`. Float
  // images with no gate at all are compared sample for sample, bit for bit.
  std::vector<metric::Gates> float_gates;
  // Percentages and means over the pixels the case's "foreground" image marks (a rendered
  // scene's geometry), so sky does not dilute them. Only for kinds that keep such an image.
  bool foreground_only = false;
  std::vector<Region> regions;        // empty: no region map is read
  std::vector<resemble::Box> ignore;  // left, top, right, bottom, in pixels
  std::filesystem::path
      mask;  // pixels where this PNG is not black (any of R, G, B > 0) are ignored
  WarnLimits warn;

  // The gates a float image is judged by: `gates`, then `float_gates`.
  std::vector<metric::Gates> gates_for(bool is_float) const;
};

// The limits that are one value each, by the names a suite's [tolerance] table and folder
// mode's `--limit KEY=VALUE` both use: sets the one named, nothing else. Throws
// std::invalid_argument, one line, for an unknown key or a value out of its range.
inline constexpr const char* kLimitKeys =
    "mode, max_mismatch_percent, max_channel_delta, max_differing_pixels, max_mean_shift, "
    "max_mean_delta, shift_radius, allow_kind_change, resemble";
void set_limit(Tolerance& t, std::string_view key, const std::string& value);

}  // namespace aosuite::comparison

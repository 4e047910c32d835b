// The one comparison: an actual image against an expected one under a Tolerance, giving every
// figure, every metric measured, every limit's outcome and the one verdict. `aosuite compare`,
// folder mode, suites (harness/judge.cpp picks among a case's golden variants) and the C++ API
// all call run(); none decides a verdict of its own.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/file_io.hpp"
#include "compare/change_regions.hpp"
#include "compare/difference_views.hpp"
#include "compare/metric.hpp"
#include "compare/resemble.hpp"
#include "compare/tolerance.hpp"
#include "image/picture.hpp"

namespace aosuite::comparison {

// One image as the comparison takes it: a file's bytes (decoded only as far as needed, and
// never when the two files are byte-identical), or a picture already in memory.
struct Input {
  std::string name;                      // for messages: the file, or "the render"
  std::span<const unsigned char> bytes;  // the file's; empty for an in-memory picture
  const Picture* picture = nullptr;      // decoded already (8-bit, 16-bit or float)
  static Input file(std::string name, std::span<const unsigned char> bytes) {
    return {std::move(name), bytes, nullptr};
  }
  static Input image(const Picture& p) { return {p.name, {}, &p}; }
};

using Counted = std::vector<std::uint8_t>;

struct Options {
  bool want_diff = false;              // Resemble's diff image, when the images are not the same
  bool want_heatmap = false;           // the heat-map metric's error map, likewise
  bool want_difference_views = false;  // Comparison::views, likewise (8-bit images)
  // width * height flags (foreground_only's geometry pixels): Resemble's mismatch, the channel
  // figures and every metric cover only the flagged pixels.
  const Counted* counted = nullptr;
  std::filesystem::path region_map;  // a tolerance with regions reads its classes here
  // Resemble.js's options beyond the tolerance's mode (`aosuite compare`'s flags: boxes, error
  // colour, canvas model); the result is kept in Comparison::resemble. Null: the tolerance's.
  const resemble::Options* resemble_options = nullptr;
  std::uint64_t max_bytes = kMaxFileBytes;  // what decoding either file may take
  bool tool_pooling = false;  // metric::Request::tool_pooling (`compare --flip-pooling tool`)
};

// Where the images differ most (idiff's "max error @ (x, y)"): the largest |actual - expected|
// of any sample (0..255 for 8-bit images, the samples' own unit for float ones) and the first
// pixel, row-major, that holds it; x = y = -1 where nothing differs.
struct LargestDifference {
  double value = 0;
  int x = -1, y = -1;
  std::string text() const;  // "12 @ (3, 4)", "0.0312 @ (3, 4)"; "" where nothing differs
};

enum class Verdict { kSame, kWarn, kDifferent };

struct Comparison {
  Verdict verdict = Verdict::kDifferent;
  std::vector<std::string> failed;  // each limit that failed, in one form everywhere
  std::vector<std::string> warned;  // each limit of the warning tier exceeded (when it passes)
  bool identical = false;           // byte-identical files: nothing was decoded or measured
  // The figures are the images' (identical, or Resemble's numbers and every gate's value are
  // theirs); false where no tolerance could make them pass (another size or kind).
  bool comparable = false;
  std::string expected_kind, actual_kind;  // "8-bit", "16-bit grey", "float colour", ...
  double mismatch_percent = 0;             // Resemble's rawMisMatchPercentage
  std::string mismatch_text;               // its misMatchPercentage ("0.42")
  int max_channel_delta = 0;               // over unignored pixels
  long long differing_pixels = 0;          // unignored pixels with any channel changed
  double mean_shift = 0, mean_delta = 0;   // ChannelStats' figures, in levels
  LargestDifference largest;
  // A passing, measured image's budgets it uses under a tenth of (verdict::stale_budgets).
  std::vector<std::string> stale;
  std::vector<metric::Measurement> measured;  // every gated metric's values
  std::vector<metric::Outcome> outcomes;      // each gate's value, limit and margin
  RgbaImage diff;                             // Resemble's diff image, when asked and not the same
  std::vector<std::uint8_t> ignored;          // with a diff: the pixels the tolerance ignored
  RgbaImage heatmap;                     // the heat-map metric's map, when asked and not the same
  std::optional<DifferenceViews> views;  // absolute and signed, when asked and not the same
  std::optional<resemble::Result> resemble;  // Resemble's own result, for `compare`'s output
  // What kind of change each changed region is (shift, brightness, added, ...): 8-bit images
  // that are not the same only.
  std::vector<ChangedRegion> changes;
  bool same() const { return verdict != Verdict::kDifferent; }
  std::string message() const;  // the failed limits, or "warning: " and the warned ones
};

// Throws FileError (or std::runtime_error) naming a file that cannot be read or decoded, a mask
// of another size or a region map that does not fit; every other outcome is a Comparison.
Comparison run(const Input& actual, const Input& expected, const Tolerance& tolerance,
               const Options& options = {});

// The pixels a tolerance's ignore boxes (inclusive corners, clipped to the frame) and mask (not
// black) take out of a width x height 8-bit comparison: 1 ignored, row-major; empty when it has
// neither. Throws std::runtime_error naming a mask of another size.
std::vector<std::uint8_t> ignored_pixels(const Tolerance& t, int width, int height);

}  // namespace aosuite::comparison

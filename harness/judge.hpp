// The verdict on one rendered image against its accepted goldens, under a case's tolerance.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "harness/suite.hpp"
#include "image/rgba_image.hpp"

namespace aosuite::harness {

// kFlaky: a case that failed, then passed when run again (--retries); never an image's verdict.
// kWarn: passed, but beyond a limit of the tolerance's warning tier; exits 0 as a pass does.
enum class Status { kPass, kFail, kNew, kError, kFlaky, kWarn };
std::string_view status_name(Status s);  // PASS FAIL NEW ERROR FLAKY WARN
// How much a status needs a person's eyes: ERROR 5, FAIL 4, NEW 3, FLAKY 2, WARN 1, PASS 0. A case
// is as severe as its worst image, and the report lists the most severe first.
int severity(Status s);
Status worst(Status a, Status b);  // the more severe; `a` on a tie
// Whether a person may accept the case's images as its goldens: FAIL, NEW and WARN (bless
// --failed takes these, and they get a printed bless command).
bool awaits_approval(Status s);
Status parse_status(std::string_view name);

// Where the render differs most from its golden (idiff's "max error @ (x, y)"): the largest
// |new - golden| of any sample (0..255 for 8-bit images, the samples' own unit for float ones)
// and the first pixel, row-major, that holds it; x = y = -1 where nothing differs.
struct LargestDifference {
  double value = 0;
  int x = -1, y = -1;
  std::string text() const;  // "12 @ (3, 4)", "0.0312 @ (3, 4)"; "" where nothing differs
};

struct ImageVerdict {
  std::string image;  // no_ao | with_ao | ao_only | ao_float, or an image case's own
  Status status = Status::kError;
  bool identical = false;          // byte-identical to the golden: nothing was compared
  double mismatch_percent = 0;     // Resemble's rawMisMatchPercentage against `golden`
  std::string mismatch_text;       // its misMatchPercentage ("0.42")
  int max_channel_delta = 0;       // largest |new - golden| over unignored pixels
  long long differing_pixels = 0;  // unignored pixels with any channel changed
  LargestDifference largest;       // over the unignored pixels; measured images only
  std::filesystem::path golden;    // the accepted golden closest to the render
  std::string message;             // why it failed or could not be judged
  // A passing, measured (not byte-identical) image's budgets it uses under a tenth of
  // (verdict::stale_budgets): tolerances to tighten.
  std::vector<std::string> stale;
  RgbaImage diff;  // Resemble's diff image, when asked and not passing
  // With a diff: the pixels the tolerance ignored (ignored_pixels()), for the report's overlay;
  // empty when it ignores none.
  std::vector<std::uint8_t> ignored;
  // The tolerance's metric gates: every gated metric's values, and each gate's outcome (value,
  // limit, margin). Empty for identical images: nothing was measured.
  std::vector<metric::Measurement> measured;
  std::vector<metric::Outcome> outcomes;
  RgbaImage heatmap;  // FLIP's error map, when FLIP is gated, asked for and not passing
  // The golden's content hash, so what was measured against it is not mistaken for numbers
  // against a golden blessed since (`tolerances suggest`); empty when it could not be read.
  std::string golden_hash;
  // The render was measured against the golden: identical, or Resemble's numbers and every gate's
  // value are the render's. False where no tolerance could make it pass (another size or kind).
  bool comparable = false;
};

// The pixels a tolerance's ignore boxes (inclusive corners, clipped to the frame) and mask (not
// black) take out of a width x height 8-bit comparison: 1 ignored, row-major; empty when it has
// neither. Throws std::runtime_error naming a mask of another size.
std::vector<std::uint8_t> ignored_pixels(const Tolerance& t, int width, int height);

// A golden's bytes as ImageVerdict::golden_hash records them.
std::string golden_hash(std::span<const unsigned char> bytes);

// Judges a render (its file's bytes, and for PNGs their decoded RGBA; `render` is empty for
// float images) against `goldens` (accepted variants; the case passes if any does) under
// Resemble's gate and the metric gates. Missing goldens give kNew; an unreadable golden or
// variant gives kError naming it, even when another variant passes; a golden of another size
// or kind kFail with both named. A float image without metric gates is compared byte for byte.
// `counted` (width * height flags; foreground_only's geometry pixels) restricts Resemble's
// mismatch percentage and every metric to the flagged pixels.
using Counted = std::vector<std::uint8_t>;
ImageVerdict judge(std::string_view image, std::span<const unsigned char> render_bytes,
                   const RgbaImage& render, const std::vector<std::filesystem::path>& goldens,
                   const Tolerance& tolerance, bool want_diff, const Counted* counted = nullptr);

}  // namespace aosuite::harness

// The verdict on one rendered image against its accepted goldens, under a case's tolerance.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "compare/comparison.hpp"
#include "harness/goldens.hpp"
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

using comparison::LargestDifference;

// One image's verdict: the comparison against the accepted golden closest to it (every figure,
// measurement and limit's outcome; nothing when it is NEW or could not be judged), and what the
// harness adds: the status, the golden, and why.
struct ImageVerdict : comparison::Comparison {
  std::string image;  // no_ao | with_ao | ao_only | ao_float, or an image case's own
  Status status = Status::kError;
  std::filesystem::path golden;  // the accepted golden closest to the render
  std::string message;           // why it failed, warned, is new or could not be judged
  // The golden's content hash, so what was measured against it is not mistaken for numbers
  // against a golden blessed since (`tolerances suggest`); empty when it could not be read.
  std::string golden_hash;
};

using comparison::ignored_pixels;

// A golden's bytes as ImageVerdict::golden_hash records them.
std::string golden_hash(std::span<const unsigned char> bytes);

// Judges a render (its file's bytes) against `goldens` (accepted variants; the case passes if
// any does) by the one comparison (comparison::run). Missing goldens give kNew; an unreadable
// golden or variant gives kError naming it, even when another variant passes. `counted`
// (width * height flags; foreground_only's geometry pixels) restricts the figures and every
// metric to the flagged pixels.
using comparison::Counted;
ImageVerdict judge(std::string_view image, std::span<const unsigned char> render_bytes,
                   const std::vector<ReadGolden>& goldens, const Tolerance& tolerance,
                   bool want_diff, const Counted* counted = nullptr);

}  // namespace aosuite::harness

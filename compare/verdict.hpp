// The one rule that turns measurements of two images into a verdict, for `compare`, `check`
// and folder mode alike: Resemble's mismatch within its allowance on images of one size, the
// largest channel difference within its allowance, and every metric gate holding. What failed
// is said in one form everywhere: "mismatch 0.42% (allowed 0.1%)", "flip mean 0.031 > 0.02".
// The callers differ only in their defaults (compare: Resemble.js's threshold 0 and no channel
// limit; a suite: its tolerance), never in the rule.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "compare/metric.hpp"

namespace aosuite::verdict {

// Two-sided budgets, as Mozilla's reftest fuzzy(minDiff-maxDiff, minPixels-maxPixels): a
// minimum above 0 says the case is known to differ by at least that much, so a difference that
// disappears (a fix, or a golden that no longer shows the known defect) fails and the budget
// is tightened, rather than left to hide the next change.
struct ResembleAllowance {
  double max_mismatch_percent = 0;
  int max_channel_delta = 255;  // 255: any (Resemble.js itself has no such limit)
  int min_channel_delta = 0;
  long long min_differing_pixels = 0, max_differing_pixels = -1;  // -1: any number
  double max_mean_shift = 255, max_mean_delta = 255;              // 255: any
};

// What Resemble's comparison found (a channel delta of -1: not measured).
struct ResembleFigures {
  bool same_size = true;
  double mismatch_percent = 0;
  std::string mismatch_text;  // Resemble's two-decimal misMatchPercentage
  int max_channel_delta = -1;
  long long differing_pixels = -1;        // pixels with any channel changed; -1: not counted
  double mean_shift = 0, mean_delta = 0;  // comparison::ChannelStats' figures
};

struct Verdict {
  bool pass = true;
  std::vector<std::string> failed;  // each failed limit, in the order above
  std::string message() const;      // "; "-joined
};

// `resemble` null: Resemble's comparison is not part of this verdict (metrics only).
Verdict decide(const ResembleFigures* resemble, const ResembleAllowance& allowed,
               std::span<const metric::Outcome> gates);

// The upper limits a measured difference uses less than a tenth of: the mismatch percentage,
// the differing pixels and metric `max` gates ("max_mismatch_percent 5 (used 0.12)"). Such a
// budget would let a change ten times this one pass: a tolerance to tighten (the channel
// delta's default and `min` gates are not listed).
std::vector<std::string> stale_budgets(const ResembleFigures* resemble,
                                       const ResembleAllowance& allowed,
                                       std::span<const metric::Outcome> gates);

}  // namespace aosuite::verdict

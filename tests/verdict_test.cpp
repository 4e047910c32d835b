// The two-sided budgets' boundaries from a second angle: verdict::decide alone, swept over every
// figure around every end of several budgets, where ImageCases.TwoSidedBudgetsFailAboveAndBelow
// checks a few points through a suite. Both ends are inclusive: lo <= figure <= hi passes.
#include "compare/verdict.hpp"

#include <gtest/gtest.h>

namespace aosuite::verdict {
namespace {

ResembleFigures figures(int channel_delta, long long differing_pixels) {
  ResembleFigures f;
  f.mismatch_text = "0.00";
  f.max_channel_delta = channel_delta;
  f.differing_pixels = differing_pixels;
  return f;
}

TEST(Verdict, AChannelDeltaBudgetHoldsExactlyItsClosedRange) {
  for (const auto& [lo, hi] : {std::pair{0, 0}, {1, 1}, {2, 8}, {0, 255}, {254, 255}}) {
    ResembleAllowance a;
    a.min_channel_delta = lo, a.max_channel_delta = hi;
    for (int d = 0; d <= 255; ++d) {
      const ResembleFigures f = figures(d, -1);
      EXPECT_EQ(decide(&f, a, {}).pass, lo <= d && d <= hi) << d << " in " << lo << ".." << hi;
    }
  }
}

TEST(Verdict, ADifferingPixelsBudgetHoldsExactlyItsClosedRange) {
  for (const auto& [lo, hi] : {std::pair{0LL, 0LL}, {1LL, 10LL}, {3LL, 3LL}, {5LL, -1LL}}) {
    ResembleAllowance a;
    a.min_differing_pixels = lo, a.max_differing_pixels = hi;
    for (long long n = 0; n <= 40; ++n) {
      const ResembleFigures f = figures(0, n);
      const bool want = lo <= n && (hi < 0 || n <= hi);
      const Verdict v = decide(&f, a, {});
      EXPECT_EQ(v.pass, want) << n << " in " << lo << ".." << hi;
      // Below the minimum the message says the known difference is gone, above it does not.
      if (!want) {
        EXPECT_EQ(v.message().find("is gone") != std::string::npos, n < lo) << v.message();
      }
    }
  }
}

// Not measured (-1) is never judged against a minimum: a figure nobody counted cannot fail.
TEST(Verdict, FiguresNotMeasuredMeetNoMinimum) {
  ResembleAllowance a;
  a.min_channel_delta = 3, a.min_differing_pixels = 3;
  const ResembleFigures f = figures(-1, -1);
  EXPECT_TRUE(decide(&f, a, {}).pass);
}

}  // namespace
}  // namespace aosuite::verdict

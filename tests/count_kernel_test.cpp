// The vectorised counter against its scalar definition, and the fast path of compare()
// against the general per-pixel path, on random images.
#include "compare/count_kernel.hpp"

#include <gtest/gtest.h>

#include <random>

#include "compare/opencv.hpp"

namespace aosuite {
namespace {

// Pairs that differ a little everywhere, a lot in places, and not at all elsewhere.
std::pair<cv::Mat, cv::Mat> random_pair(std::mt19937& rng, int w, int h) {
  cv::Mat a(h, w, CV_8UC4), b;
  cv::randu(a, 0, 256);
  b = a.clone();
  std::uniform_int_distribution<int> coin(0, 9), delta(-40, 40), x(0, w - 1), y(0, h - 1);
  const int edits = coin(rng) * w * h / 10;
  for (int i = 0; i < edits; ++i) {
    cv::Vec4b& p = b.at<cv::Vec4b>(y(rng), x(rng));
    const int c = coin(rng) % 4;
    p[c] = cv::saturate_cast<uchar>(p[c] + delta(rng));
  }
  return {a, b};
}

TEST(CountKernel, MatchesScalarDefinition) {
  std::mt19937 rng(7);
  const int sizes[][2] = {{1, 1}, {15, 3}, {16, 1}, {17, 5}, {33, 31}, {100, 7}, {640, 480}};
  const std::array<int, 4> deltas[] = {
      {16, 16, 16, 16}, {1, 1, 1, 1}, {33, 1, 256, 256}, {256, 256, 256, 256}, {11, 11, 11, 256}};
  for (const auto& s : sizes) {
    for (const auto& d : deltas) {
      const auto [a, b] = random_pair(rng, s[0], s[1]);
      const MismatchTally fast = count_mismatches(a.data, b.data, s[0], s[1], d);
      const MismatchTally ref = count_mismatches_scalar(a.data, b.data, s[0], s[1], d);
      ASSERT_EQ(fast.count, ref.count) << s[0] << "x" << s[1];
      if (ref.count) {
        EXPECT_EQ(fast.top, ref.top);
        EXPECT_EQ(fast.left, ref.left);
        EXPECT_EQ(fast.bottom, ref.bottom);
        EXPECT_EQ(fast.right, ref.right);
      }
    }
  }
}

TEST(CountKernel, FastPathAgreesWithPerPixelPath) {
  std::mt19937 rng(11);
  using resemble::Mode;
  for (Mode m : {Mode::kDefault, Mode::kNothing, Mode::kLess, Mode::kAlpha}) {
    for (double red : {-1.0, 0.0, 10.5, 16.0, 300.0}) {
      const auto [a, b] = random_pair(rng, 67, 45);
      resemble::Options o;
      if (m != Mode::kDefault) o.modes = {m};
      o.tolerance.red = red;
      const resemble::Result fast = resemble::compare(a, b, o);
      o.produce_diff = true;  // forces the per-pixel path
      const resemble::Result slow = resemble::compare(a, b, o);
      EXPECT_EQ(fast.mismatch_count, slow.mismatch_count);
      EXPECT_EQ(fast.raw_mismatch_percentage, slow.raw_mismatch_percentage);
      EXPECT_TRUE(fast.diff_bounds == slow.diff_bounds);
    }
  }
}

}  // namespace
}  // namespace aosuite

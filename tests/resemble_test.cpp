// Each quirk of Resemble.js 5.0.0 with its expected value derived by hand from the rule each
// test names (resemble.js 5.0.0's source; docs/compare.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "compare/js_number.hpp"
#include "compare/opencv.hpp"
#include "compare/resemble_pixel.hpp"

namespace aosuite::resemble {
namespace {

cv::Mat solid(int w, int h, cv::Vec4b c) {
  return cv::Mat(h, w, CV_8UC4, cv::Scalar(c[0], c[1], c[2], c[3]));
}

cv::Vec4b diff_at(const Result& r, int y, int x) { return to_mat(r.diff).at<cv::Vec4b>(y, x); }

Options with_mode(Mode m) {
  Options o;
  o.modes = {m};
  return o;
}

const cv::Vec4b kBlack(0, 0, 0, 255), kWhite(255, 255, 255, 255);

TEST(Resemble, LessAcceptsFifteenRejectsSixteen) {
  const cv::Mat a = solid(1, 1, {100, 100, 100, 255});
  EXPECT_EQ(compare(a, solid(1, 1, {115, 100, 100, 255}), with_mode(Mode::kLess)).mismatch_count,
            0u);
  EXPECT_EQ(compare(a, solid(1, 1, {116, 100, 100, 255}), with_mode(Mode::kLess)).mismatch_count,
            1u);
  EXPECT_EQ(compare(a, solid(1, 1, {101, 100, 100, 255}), with_mode(Mode::kNothing)).mismatch_count,
            1u);
  EXPECT_EQ(compare(a, a, with_mode(Mode::kNothing)).mismatch_count, 0u);
}

TEST(Resemble, CustomToleranceNeedsAMode) {
  Options o;
  o.tolerance.red = 0;
  const cv::Mat a = solid(1, 1, {100, 100, 100, 255}), b = solid(1, 1, {110, 100, 100, 255});
  EXPECT_EQ(compare(a, b, o).mismatch_count, 0u);  // no mode: silently ignored
  o.modes = {Mode::kLess};
  EXPECT_EQ(compare(a, b, o).mismatch_count, 1u);
  o.tolerance.red = 10.5;  // |d| < 10.5 holds for 10
  EXPECT_EQ(compare(a, b, o).mismatch_count, 0u);
}

// Every mode a suite or batch line may name reads back as itself; names are case-sensitive.
TEST(Resemble, ModeNamesRoundTrip) {
  for (const char* name : {"default", "nothing", "less", "colors", "antialiasing", "alpha"}) {
    EXPECT_EQ(mode_name(parse_mode(name)), name);
  }
  EXPECT_NE(parse_mode("less"), parse_mode("alpha"));
  EXPECT_THROW(parse_mode("Less"), std::invalid_argument);
  EXPECT_THROW(parse_mode(""), std::invalid_argument);
}

// A batch line's mode is quoted escaped in the error (found by fuzz/compare_options_fuzz.cpp).
TEST(Resemble, UnknownModeIsQuotedEscaped) {
  try {
    parse_mode("\x1b[31mred");
    FAIL() << "an unknown mode was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("unknown mode '\\x1b[31mred' (expected", 0), 0u)
        << e.what();
  }
}

TEST(Resemble, AlphaModeIgnoresAlpha) {
  const cv::Mat a = solid(1, 1, {100, 100, 100, 255}), b = solid(1, 1, {100, 100, 100, 55});
  EXPECT_EQ(compare(a, b, with_mode(Mode::kLess)).mismatch_count, 1u);
  EXPECT_EQ(compare(a, b, with_mode(Mode::kAlpha)).mismatch_count, 0u);
}

TEST(Resemble, ColorsModeComparesBrightnessAndPaintsGrey) {
  // brightness 0.3*100 = 30 and 0.59*51 = 30.09: similar under 16, though the hues differ.
  Options o = with_mode(Mode::kColors);
  o.produce_diff = true;
  const Result r = compare(solid(1, 1, {100, 0, 0, 255}), solid(1, 1, {0, 51, 0, 255}), o);
  EXPECT_EQ(r.mismatch_count, 0u);
  EXPECT_EQ(diff_at(r, 0, 0), cv::Vec4b(30, 30, 30, 255));  // grey of image 2
}

TEST(Resemble, MisMatchPercentageTieRoundsUp) {
  cv::Mat b = solid(32, 1, kBlack);
  b.at<cv::Vec4b>(0, 7) = kWhite;
  const Result r = compare(solid(32, 1, kBlack), b, {});
  EXPECT_EQ(r.raw_mismatch_percentage, 3.125);
  EXPECT_EQ(r.mismatch_percentage, "3.13");
  EXPECT_EQ(r.diff_bounds.left, 7);
  EXPECT_EQ(r.diff_bounds.right, 7);
}

TEST(Resemble, RawPercentageIsCountOverPixelsTimesHundred) {
  cv::Mat b = solid(3, 3, kBlack);
  for (int i = 0; i < 6; ++i) b.at<cv::Vec4b>(i / 3, i % 3) = kWhite;
  const Result r = compare(solid(3, 3, kBlack), b, {});
  const double expected = (6.0 / 9.0) * 100;  // 66.66666666666666, not 66.66666666666667
  EXPECT_EQ(std::memcmp(&r.raw_mismatch_percentage, &expected, sizeof expected), 0);
  EXPECT_EQ(r.mismatch_percentage, "66.67");
}

TEST(Resemble, NoMismatchLeavesInitialBounds) {
  const Result r = compare(solid(5, 4, kBlack), solid(5, 4, kBlack), {});
  EXPECT_EQ(r.diff_bounds.top, 4);
  EXPECT_EQ(r.diff_bounds.left, 5);
  EXPECT_EQ(r.diff_bounds.bottom, 0);
  EXPECT_EQ(r.diff_bounds.right, 0);
}

TEST(Resemble, LargeImagesSkipEverySixthLineOnlyInAntialiasingMode) {
  const cv::Mat a = solid(1300, 100, kBlack), b = solid(1300, 100, kWhite);
  // 1083 of 1300 columns and 83 of 100 rows are not multiples of 6.
  const Result aa = compare(a, b, with_mode(Mode::kAntialiasing));
  EXPECT_EQ(aa.raw_mismatch_percentage, (1083.0 * 83 / 130000) * 100);
  EXPECT_EQ(js_number_to_string(aa.raw_mismatch_percentage), "69.14538461538461");
  EXPECT_EQ(compare(a, b, with_mode(Mode::kLess)).raw_mismatch_percentage, 100);
  Options off = with_mode(Mode::kAntialiasing);
  off.large_image_threshold = 0;
  EXPECT_EQ(compare(a, b, off).raw_mismatch_percentage, 100);
}

TEST(Resemble, SmallerImageIsPaddedWithTransparentBlack) {
  const cv::Vec4b red(255, 0, 0, 255);
  const Result r = compare(solid(2, 2, red), solid(3, 3, red), {});
  EXPECT_FALSE(r.same_dimensions);
  EXPECT_EQ(r.width_difference, -1);
  EXPECT_EQ(r.height_difference, -1);
  EXPECT_EQ(r.mismatch_count, 5u);  // the padded L-shaped border
  EXPECT_EQ(js_number_to_string(r.raw_mismatch_percentage), "55.55555555555556");
  EXPECT_EQ(r.diff_bounds.top, 0);
  EXPECT_EQ(r.diff_bounds.left, 0);
  EXPECT_EQ(r.diff_bounds.bottom, 2);
  EXPECT_EQ(r.diff_bounds.right, 2);
}

TEST(Resemble, EarlyReturnStopsInColumnMajorOrder) {
  Options o;
  o.return_early_threshold = 5;
  o.produce_diff = true;
  // 204/4096 = 4.98 %, 205/4096 = 5.0049 %: the 205th mismatch, in column-major order
  // (x outer, y inner), is (3, 12).
  const Result r = compare(solid(64, 64, kBlack), solid(64, 64, kWhite), o);
  EXPECT_EQ(r.mismatch_count, 205u);
  EXPECT_EQ(r.raw_mismatch_percentage, 5.0048828125);
  EXPECT_EQ(r.diff_bounds.left, 0);
  EXPECT_EQ(r.diff_bounds.right, 3);
  EXPECT_EQ(r.diff_bounds.top, 0);
  EXPECT_EQ(r.diff_bounds.bottom, 63);
  EXPECT_TRUE(r.diff.empty());  // compareOnly: no diff image
}

TEST(Resemble, EarlyReturnBoundsCoverOnlyCountedPixels) {
  Options o;
  o.return_early_threshold = 1;
  cv::Mat b = solid(10, 10, kBlack);
  b.at<cv::Vec4b>(9, 1) = kWhite;  // (1, 9): first in column-major order
  b.at<cv::Vec4b>(0, 2) = kWhite;  // (2, 0): second, 2 % > 1 % -> stop here
  b.at<cv::Vec4b>(5, 8) = kWhite;  // (8, 5): never reached
  const Result r = compare(solid(10, 10, kBlack), b, o);
  EXPECT_EQ(r.mismatch_count, 2u);
  EXPECT_EQ(r.diff_bounds.left, 1);
  EXPECT_EQ(r.diff_bounds.top, 0);
  EXPECT_EQ(r.diff_bounds.bottom, 9);
  EXPECT_EQ(r.diff_bounds.right, 2);
}

TEST(Resemble, NegativeEarlyThresholdStopsAfterTheFirstPixel) {
  Options o;
  o.return_early_threshold = -1;
  const Result r = compare(solid(8, 8, kBlack), solid(8, 8, kWhite), o);
  EXPECT_EQ(r.mismatch_count, 1u);
  EXPECT_EQ(r.diff_bounds.right, 0);
  EXPECT_EQ(r.diff_bounds.bottom, 0);
}

TEST(Resemble, BoxesAreStrictAndZeroMeansTheImageEdge) {
  const cv::Mat a = solid(4, 4, kBlack), b = solid(4, 4, kWhite);
  Options o;
  o.bounding_boxes = std::vector<Box>{{1, 1, 3, 3}};
  EXPECT_EQ(compare(a, b, o).mismatch_count, 1u);  // only (2, 2) is strictly inside
  o.bounding_boxes = std::vector<Box>{{0, 0, 0, 0}};
  EXPECT_EQ(compare(a, b, o).mismatch_count, 9u);  // row 0 and column 0 never inside
  o.bounding_boxes = std::vector<Box>{};
  EXPECT_EQ(compare(a, b, o).mismatch_count, 0u);  // an empty list selects nothing
  o.bounding_boxes.reset();
  o.ignored_boxes = std::vector<Box>{{1, 1, 3, 3}};
  EXPECT_EQ(compare(a, b, o).mismatch_count, 15u);
}

TEST(Resemble, IgnoreAreasColoredWithOverridesBoxes) {
  cv::Mat b = solid(4, 1, kWhite);
  b.at<cv::Vec4b>(0, 2) = cv::Vec4b(1, 2, 3, 255);
  Options o;
  o.bounding_boxes = std::vector<Box>{};  // would exclude everything
  o.ignore_areas_colored_with = Color{1, 2, 3, 255};
  EXPECT_EQ(compare(solid(4, 1, kBlack), b, o).mismatch_count, 3u);
}

Result one_error(ErrorType type, cv::Vec4b p1, cv::Vec4b p2, Color e = {}) {
  Options o = with_mode(Mode::kNothing);
  o.error_type = type;
  o.error_color = e;
  o.produce_diff = true;
  return compare(solid(1, 1, p1), solid(1, 1, p2), o);
}

TEST(Resemble, DiffImageErrorStylesRoundHalfToEven) {
  const cv::Vec4b p1(0, 0, 0, 255), p2(98, 50, 200, 255);
  auto px = [](const Result& r) { return diff_at(r, 0, 0); };
  EXPECT_EQ(px(one_error(ErrorType::kFlat, p1, p2)), cv::Vec4b(255, 0, 255, 255));
  // (98 + 255) / 2 = 176.5 -> 176 and (200 + 255) / 2 = 227.5 -> 228: ties to even
  EXPECT_EQ(px(one_error(ErrorType::kMovement, p1, p2)), cv::Vec4b(176, 0, 228, 255));
  // alpha = (98 + 50 + 200) / 3 = 116
  EXPECT_EQ(px(one_error(ErrorType::kFlatDifferenceIntensity, p1, p2)),
            cv::Vec4b(255, 0, 255, 116));
  EXPECT_EQ(px(one_error(ErrorType::kDiffOnly, p1, p2)), p2);
  EXPECT_EQ(px(one_error(ErrorType::kFlat, p1, p2, {2.5, 3.5, 0.5, 255})), cv::Vec4b(2, 4, 0, 255));
  // k = (255 / 255) * 0.8: (1 - k) * 255 + k * 255 = 255 on red and blue, 0 on green
  EXPECT_EQ(px(one_error(ErrorType::kMovementDifferenceIntensity, p1, kWhite)),
            cv::Vec4b(255, 0, 255, 255));
}

TEST(Resemble, TransparencyScalesOnlyMatchingPixels) {
  Options o;
  o.transparency = 0.5;
  o.produce_diff = true;
  cv::Mat b = solid(2, 1, {10, 20, 30, 255});
  b.at<cv::Vec4b>(0, 1) = kWhite;
  const Result r = compare(solid(2, 1, {10, 20, 30, 255}), b, o);
  EXPECT_EQ(diff_at(r, 0, 0), cv::Vec4b(10, 20, 30, 128));  // 127.5 -> 128
  EXPECT_EQ(diff_at(r, 0, 1), cv::Vec4b(255, 0, 255, 255));
}

TEST(Resemble, DiffOnlyLeavesMatchingPixelsEmpty) {
  Options o;
  o.error_type = ErrorType::kDiffOnly;
  o.produce_diff = true;
  const Result r = compare(solid(1, 1, {10, 20, 30, 255}), solid(1, 1, {10, 20, 30, 255}), o);
  EXPECT_EQ(diff_at(r, 0, 0), cv::Vec4b(0, 0, 0, 0));
}

TEST(ResemblePixel, HueIsNotDividedBySix) {
  EXPECT_EQ(pixel::hue({0, 255, 0, 255}), 2.0);
  EXPECT_EQ(pixel::hue({0, 0, 255, 255}), 4.0);
  EXPECT_EQ(pixel::hue({128, 128, 128, 255}), 0.0);
  EXPECT_DOUBLE_EQ(pixel::hue({255, 0, 128, 255}), 6.0 - 128.0 / 255.0);
}

TEST(ResemblePixel, BrightnessIsNotFused) {
  // Find a pixel whose brightness differs when the sum is fused; ours must be the unfused one.
  int found = 0;
  for (int r = 0; r < 256 && !found; ++r) {
    for (int g = 0; g < 256 && !found; g += 3) {
      for (int b = 0; b < 256; b += 7) {
        volatile double x = 0.3 * r, y = 0.59 * g, z = 0.11 * b;
        const double plain = (x + y) + z;
        const double fused = std::fma(0.11, b, std::fma(0.59, g, 0.3 * r));
        if (plain != fused) {
          EXPECT_EQ(pixel::brightness({r, g, b, 255}), plain);
          found = 1;
          break;
        }
      }
    }
  }
  EXPECT_TRUE(found);
}

TEST(ResemblePixel, AntialiasingNeighboursWrapAcrossRows) {
  // 4x3 greys, (0, 1) darker. By linear index its left neighbours are (3, 0) and (3, 1),
  // the previous row's last pixels; (x-1, y-1) is index -1, which reads undefined.
  const cv::Vec4b bg(130, 130, 130, 255), c(100, 100, 100, 255);
  cv::Mat img = solid(4, 3, bg);
  img.at<cv::Vec4b>(1, 0) = c;
  const pixel::Px src{100, 100, 100, 255};
  // no equal neighbour, no contrast (30 <= 96), no hue difference: antialiased
  EXPECT_TRUE(pixel::antialiased(img.data, 4, 3, src, 0, 1, 96));
  img.at<cv::Vec4b>(0, 3) = c;
  img.at<cv::Vec4b>(1, 3) = c;
  // two equal neighbours through the wrap: not antialiased
  EXPECT_FALSE(pixel::antialiased(img.data, 4, 3, src, 0, 1, 96));
}

TEST(Resemble, AnImageNeverDiffersFromItself) {
  // compare_identical stands in for compare(x, x, ...) on byte-identical files.
  cv::Mat x(33, 21, CV_8UC4);
  cv::randu(x, 0, 256);
  std::vector<Options> cases(6);
  cases[0].modes = {Mode::kNothing};
  cases[1].modes = {Mode::kAntialiasing};
  cases[1].large_image_threshold = 10;
  cases[2].modes = {Mode::kColors};
  cases[3].ignored_boxes = std::vector<Box>{{1, 1, 5, 5}};
  cases[3].canvas_alpha = CanvasAlpha::kChromium;
  cases[4].return_early_threshold = 1e-9;
  cases[5].tolerance.red = 0;
  cases[5].modes = {Mode::kLess};
  const Result same = compare_identical({x.cols, x.rows});
  for (const Options& o : cases) {
    const Result r = compare(x, x, o);
    EXPECT_EQ(r.mismatch_count, same.mismatch_count);
    EXPECT_EQ(r.mismatch_percentage, same.mismatch_percentage);
    EXPECT_EQ(r.raw_mismatch_percentage, same.raw_mismatch_percentage);
    EXPECT_EQ(r.same_dimensions, same.same_dimensions);
    EXPECT_TRUE(r.diff_bounds == same.diff_bounds);
  }
  EXPECT_EQ(same.diff_bounds.top, 33);  // Resemble's untouched initial bounds
  EXPECT_EQ(same.diff_bounds.left, 21);
}

TEST(ResemblePixel, ClampRoundsHalfToEven) {
  EXPECT_EQ(pixel::u8clamp(0.5), 0);
  EXPECT_EQ(pixel::u8clamp(1.5), 2);
  EXPECT_EQ(pixel::u8clamp(2.5), 2);
  EXPECT_EQ(pixel::u8clamp(-3), 0);
  EXPECT_EQ(pixel::u8clamp(300), 255);
  EXPECT_EQ(pixel::u8clamp(std::nan("")), 0);
}

TEST(CanvasAlpha, ChromiumAndNodeRoundTrips) {
  auto seen = [](cv::Vec4b p, CanvasAlpha m) {
    RgbaImage img(1, 1);
    std::copy_n(p.val, 4, img.data());
    apply_canvas_decode(img, m);
    return cv::Vec4b(img.data());
  };
  // premultiplied: round(101 * 128 / 255) = 51; back: 51 * 255 / 128 = 101.6
  EXPECT_EQ(seen({101, 0, 0, 128}, CanvasAlpha::kChromium)[0], 102);    // rounds
  EXPECT_EQ(seen({101, 0, 0, 128}, CanvasAlpha::kNodeCanvas)[0], 101);  // truncates
  EXPECT_EQ(seen({101, 7, 9, 0}, CanvasAlpha::kChromium), cv::Vec4b(0, 0, 0, 0));
  EXPECT_EQ(seen({101, 7, 9, 255}, CanvasAlpha::kChromium), cv::Vec4b(101, 7, 9, 255));
  EXPECT_EQ(seen({101, 0, 0, 128}, CanvasAlpha::kNone)[0], 101);
}

}  // namespace
}  // namespace aosuite::resemble

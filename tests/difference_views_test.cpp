// The report's absolute and signed difference views (compare/difference_views.hpp): scaled so
// the largest change is full white or full colour, however small it is.
#include "compare/difference_views.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstring>

namespace aosuite::comparison {
namespace {

using Pixel = std::array<unsigned char, 4>;

RgbaImage filled(int w, int h, unsigned char grey) {
  RgbaImage img(w, h);
  for (int i = 0; i < w * h; ++i)
    std::memcpy(img.data() + 4 * i, Pixel{grey, grey, grey, 255}.data(), 4);
  return img;
}
Pixel at(const RgbaImage& img, int i) {
  Pixel p;
  std::memcpy(p.data(), img.data() + 4 * i, 4);
  return p;
}

TEST(DifferenceViews, TheLargestChangeIsFullScaleInBothViews) {
  const RgbaImage expected = filled(4, 3, 100);
  RgbaImage actual = filled(4, 3, 100);
  actual.data()[4 * 1 + 0] = 120;                             // pixel 1: red +20
  for (int c = 0; c < 3; ++c) actual.data()[4 * 5 + c] = 90;  // pixel 5: every channel -10
  const DifferenceViews v = difference_views(expected, actual);
  EXPECT_EQ(v.largest_channel, 20);
  EXPECT_DOUBLE_EQ(v.largest_signed, 10);
  EXPECT_EQ(at(v.absolute, 1), (Pixel{255, 0, 0, 255}));      // 20 of 20
  EXPECT_EQ(at(v.absolute, 5), (Pixel{128, 128, 128, 255}));  // 10 of 20
  EXPECT_EQ(at(v.absolute, 0), (Pixel{0, 0, 0, 255}));
  EXPECT_EQ(at(v.signed_change, 5), (Pixel{59, 76, 192, 255}));  // -10 of 10: the cool end
  EXPECT_EQ(at(v.signed_change, 0), (Pixel{255, 255, 255, 255}));
  // Pixel 1: +20/3 of 10, two thirds of the way from white to the warm end.
  const Pixel warm = at(v.signed_change, 1);
  EXPECT_EQ(warm[0], 205);  // 255 + (2/3)(180 - 255)
  EXPECT_EQ(warm[1], 88);   // 255 + (2/3)(4 - 255)
  EXPECT_EQ(warm[2], 110);  // 255 + (2/3)(38 - 255)
}

// A 2 % brightness change, 5 levels everywhere, is as white and as red as a large one.
TEST(DifferenceViews, ASmallUniformChangeIsStillPlain) {
  const DifferenceViews v = difference_views(filled(3, 3, 200), filled(3, 3, 205));
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(at(v.absolute, i), (Pixel{255, 255, 255, 255}));
    EXPECT_EQ(at(v.signed_change, i), (Pixel{180, 4, 38, 255}));
  }
}

TEST(DifferenceViews, NoChangeIsBlackAndWhiteWithoutDividingByZero) {
  const DifferenceViews v = difference_views(filled(2, 2, 7), filled(2, 2, 7));
  EXPECT_EQ(v.largest_channel, 0);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(at(v.absolute, i), (Pixel{0, 0, 0, 255}));
    EXPECT_EQ(at(v.signed_change, i), (Pixel{255, 255, 255, 255}));
  }
}

}  // namespace
}  // namespace aosuite::comparison

// changed_regions names each kind of change on generated pictures: for several seeds, a shift of
// the whole frame or of one object, a brightness and a colour change of a patch, an object
// added or removed over a flat background, and scattered noise. Each must come out as its kind
// (the largest region), with the shift's offset and the brightness change's sign.
#include "compare/change_regions.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace aosuite::comparison {
namespace {

constexpr int kW = 96, kH = 72;

void put(RgbaImage& img, int x, int y, int r, int g, int b) {
  unsigned char* p = img.data() + 4 * (std::size_t(y) * kW + std::size_t(x));
  p[0] = static_cast<unsigned char>(std::clamp(r, 0, 255));
  p[1] = static_cast<unsigned char>(std::clamp(g, 0, 255));
  p[2] = static_cast<unsigned char>(std::clamp(b, 0, 255)), p[3] = 255;
}

// A textured frame: gradients with per-pixel grain, values kept inside 30..220.
RgbaImage textured(std::mt19937& rng) {
  RgbaImage img(kW, kH);
  std::uniform_int_distribution<int> grain(-12, 12);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      put(img, x, y, 40 + x + grain(rng), 40 + 2 * y + grain(rng), 120 + grain(rng));
  return img;
}

// A flat sky with a textured box (an object) at (x0, y0).
RgbaImage object_on_sky(int x0, int y0, int size, bool with_object) {
  RgbaImage img(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) put(img, x, y, 150, 180, 220);
  if (!with_object) return img;
  for (int y = y0; y < y0 + size; ++y)
    for (int x = x0; x < x0 + size; ++x)
      put(img, x, y, 60 + 7 * ((x + y) % 5), 50, 40 + 3 * (x % 7));
  return img;
}

RgbaImage copy(const RgbaImage& from) {
  RgbaImage to(from.width(), from.height());
  std::copy_n(from.data(), from.view().bytes(), to.data());
  return to;
}

ChangedRegion largest(const RgbaImage& e, const RgbaImage& a) {
  const std::vector<ChangedRegion> r = changed_regions(e, a);
  EXPECT_FALSE(r.empty());
  return r.empty() ? ChangedRegion{} : r.front();
}

class ChangeKinds : public ::testing::TestWithParam<unsigned> {};

TEST_P(ChangeKinds, EachGeneratedKindIsNamed) {
  std::mt19937 rng(GetParam());
  std::uniform_int_distribution<int> pos(8, 40), size(10, 20), step(1, 2);
  const RgbaImage base = textured(rng);

  // The whole frame moved right by 1 (a camera or projection change).
  RgbaImage moved = copy(base);
  for (int y = 0; y < kH; ++y)
    for (int x = kW - 1; x > 0; --x)
      std::copy_n(base.data() + 4 * (std::size_t(y) * kW + std::size_t(x - 1)), 4,
                  moved.data() + 4 * (std::size_t(y) * kW + std::size_t(x)));
  ChangedRegion r = largest(base, moved);
  EXPECT_EQ(r.kind, ChangeKind::kShift) << r.text();
  EXPECT_EQ(r.dx, 1) << r.text();
  EXPECT_EQ(r.dy, 0) << r.text();

  // One object moved by (dx, dy) over the sky.
  const int x0 = pos(rng), y0 = pos(rng), s = size(rng), dx = step(rng), dy = -step(rng);
  r = largest(object_on_sky(x0, y0, s, true), object_on_sky(x0 + dx, y0 + dy, s, true));
  EXPECT_EQ(r.kind, ChangeKind::kShift) << r.text();
  EXPECT_EQ(r.dx, dx) << r.text();
  EXPECT_EQ(r.dy, dy) << r.text();

  // A patch brighter (or darker) by the same amount in R, G and B; a patch tinted.
  const int delta = std::uniform_int_distribution<int>(3, 12)(rng) * (GetParam() % 2 ? 1 : -1);
  RgbaImage lit = copy(base), tinted = copy(base), warmer = copy(base);
  for (int y = y0; y < y0 + s; ++y) {
    for (int x = x0; x < x0 + s; ++x) {
      const unsigned char* p = base.data() + 4 * (std::size_t(y) * kW + std::size_t(x));
      put(lit, x, y, p[0] + delta, p[1] + delta, p[2] + delta);
      put(tinted, x, y, p[0] + 10, p[1] - 6, p[2]);
      put(warmer, x, y, p[0] + 24, p[1] + 8, p[2] + 4);  // every channel up, unequally
    }
  }
  r = largest(base, lit);
  EXPECT_EQ(r.kind, ChangeKind::kBrightness) << r.text();
  EXPECT_EQ(r.mean[0] > 0, delta > 0) << r.text();
  r = largest(base, tinted);
  EXPECT_EQ(r.kind, ChangeKind::kColour) << r.text();
  r = largest(base, warmer);
  EXPECT_EQ(r.kind, ChangeKind::kColour) << r.text();

  // An object that appears, or disappears, over the sky.
  r = largest(object_on_sky(x0, y0, s, false), object_on_sky(x0, y0, s, true));
  EXPECT_EQ(r.kind, ChangeKind::kAdded) << r.text();
  r = largest(object_on_sky(x0, y0, s, true), object_on_sky(x0, y0, s, false));
  EXPECT_EQ(r.kind, ChangeKind::kRemoved) << r.text();

  // Grain of +-1..2 levels on a fifth of the pixels.
  RgbaImage noisy = copy(base);
  std::uniform_int_distribution<int> pick(0, 4), amount(-2, 2);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      if (pick(rng) != 0) continue;
      const unsigned char* p = base.data() + 4 * (std::size_t(y) * kW + std::size_t(x));
      put(noisy, x, y, p[0] + amount(rng), p[1] + amount(rng), p[2] + amount(rng));
    }
  }
  r = largest(base, noisy);
  EXPECT_EQ(r.kind, ChangeKind::kNoise) << r.text();

  // A hole cut in an RGBA render: alpha 255 -> 0, the colour kept; and faded in again.
  RgbaImage holed = copy(base);
  for (int y = y0; y < y0 + s; ++y) {
    for (int x = x0; x < x0 + s; ++x)
      holed.data()[4 * (std::size_t(y) * kW + std::size_t(x)) + 3] = 0;
  }
  r = largest(base, holed);
  EXPECT_EQ(r.kind, ChangeKind::kOpacity) << r.text();
  EXPECT_NE(r.text().find("more transparent (alpha -255.0 levels)"), std::string::npos) << r.text();
  EXPECT_EQ(largest(holed, base).kind, ChangeKind::kOpacity);
}

INSTANTIATE_TEST_SUITE_P(Seeds, ChangeKinds, ::testing::Range(1u, 9u));

TEST(ChangeRegions, IdenticalAndIgnoredPixelsHaveNoRegion) {
  std::mt19937 rng(3);
  const RgbaImage a = textured(rng);
  EXPECT_TRUE(changed_regions(a, a).empty());
  RgbaImage b = copy(a);
  put(b, 5, 5, 0, 0, 0);
  std::vector<std::uint8_t> ignored(std::size_t(kW) * kH, 0);
  ignored[5 * kW + 5] = 1;
  EXPECT_TRUE(changed_regions(a, b, ignored).empty());
  ASSERT_EQ(changed_regions(a, b).size(), 1u);
  EXPECT_EQ(changed_regions(a, b).front().pixels, 1);
}

// The analysis holds 13 bytes a pixel at most, and stays within the memory it is given: a pair
// whose analysis would not fit is left undescribed rather than allowed past the limit.
TEST(ChangeRegions, AnalysisStaysWithinItsMemoryLimit) {
  std::mt19937 rng(5);
  const RgbaImage a = textured(rng);
  RgbaImage b = copy(a);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) put(b, x, y, 0, 0, 0);  // every pixel changed
  const std::uint64_t need = 13 * std::uint64_t(kW) * kH;
  EXPECT_FALSE(changed_regions(a, b, {}, 8, need).empty());
  EXPECT_TRUE(changed_regions(a, b, {}, 8, need - 1).empty());
}

}  // namespace
}  // namespace aosuite::comparison

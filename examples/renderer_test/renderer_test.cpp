// A tiny "renderer" (a shaded disc) and its tests, as a renderer team writes them with aosuite:
// each frame is judged against its golden; AOSUITE_UPDATE_GOLDENS=1 accepts new ones.
#include <gtest/gtest.h>

#include <aosuite/aosuite.hpp>
#include <cmath>
#include <filesystem>

namespace {

// A disc lit from the upper left over a grey floor; `light` moves the light.
aosuite::Image render(int width, int height, float light = 0.6f) {
  aosuite::Image img{width, height, std::vector<unsigned char>(std::size_t(width) * height * 4)};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float u = (x + 0.5f) / width * 2 - 1, v = (y + 0.5f) / height * 2 - 1;
      const float r2 = u * u + v * v;
      float shade = 0.25f;
      if (r2 < 0.6f) {
        const float z = std::sqrt(1 - r2 / 0.6f);
        shade = std::fmax(0.f, -light * u - light * v + z * 0.5f);
      }
      unsigned char* p = &img.rgba[(std::size_t(y) * width + x) * 4];
      p[0] = p[1] = p[2] = static_cast<unsigned char>(std::fmin(255.f, shade * 255.f));
      p[3] = 255;
    }
  }
  return img;
}

TEST(Renderer, DiscMatchesItsGolden) {
  EXPECT_TRUE(aosuite::matches_golden(render(64, 48), GOLDENS "/disc.png"));
}

TEST(Renderer, AMovedLightIsCaught) {
  const aosuite::Verdict v = aosuite::matches_golden(render(64, 48, 0.7f), GOLDENS "/disc.png");
  EXPECT_EQ(v.status, aosuite::Verdict::Status::kFail) << v;
  EXPECT_GT(v.mismatch_percent, 1);
  // A perceptual budget instead: FLIP's mean error may be small but not this large.
  EXPECT_FALSE(aosuite::matches_golden(render(64, 48, 0.7f), GOLDENS "/disc.png",
                                       {.gates = {"flip.max_mean=0.001"}}));
}

TEST(Renderer, ToleranceAbsorbsSmallChanges) {
  aosuite::Image a = render(64, 48), b = a;
  b.rgba[0] = static_cast<unsigned char>(b.rgba[0] + 3);  // one channel of one pixel
  EXPECT_FALSE(aosuite::compare(a, b));
  EXPECT_TRUE(aosuite::compare(a, b, {.mode = "less"}));  // Resemble's 16-level tolerance
}

TEST(Renderer, AMissingGoldenIsNew) {
  const aosuite::Verdict v = aosuite::matches_golden(render(8, 8), GOLDENS "/none/missing.png");
  EXPECT_EQ(v.status, aosuite::Verdict::Status::kNew) << v;
}

}  // namespace

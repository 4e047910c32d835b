// A tiny "renderer" (a shaded disc) and its tests, as a renderer team writes them with aosuite:
// each frame is judged against its golden by the CLI's own tolerance; a failure names the limits
// that failed and writes the actual image and the diff (their paths in the message);
// AOSUITE_UPDATE_GOLDENS=1 accepts new goldens.
#include <gtest/gtest.h>

#include <aosuite/aosuite.hpp>
#include <aosuite/gtest.hpp>
#include <cmath>
#include <filesystem>

namespace {

// A disc lit from the upper left over a grey floor; `light` moves the light.
aosuite::Image render(int width, int height, float light = 0.6f, float gain = 1.0f) {
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
      p[0] = p[1] = p[2] = static_cast<unsigned char>(std::fmin(255.f, gain * shade * 255.f));
      p[3] = 255;
    }
  }
  return img;
}

TEST(Renderer, DiscMatchesItsGolden) { EXPECT_MATCHES_GOLDEN(render(64, 48), GOLDENS "/disc.png"); }

TEST(Renderer, AMovedLightIsCaughtAndItsImagesWritten) {
  const std::filesystem::path failures = std::filesystem::temp_directory_path() / "aosuite-ex";
  setenv("AOSUITE_FAILURES", failures.c_str(), 1);
  const aosuite::Verdict v = aosuite::matches_golden(render(64, 48, 0.7f), GOLDENS "/disc.png", {},
                                                     "Renderer.AMovedLight");
  EXPECT_EQ(v.status, aosuite::Verdict::Status::kFail) << v;
  EXPECT_GT(v.mismatch_percent, 1);
  EXPECT_TRUE(std::filesystem::exists(v.actual_file)) << v;
  EXPECT_TRUE(std::filesystem::exists(v.diff_file)) << v;
  // A perceptual budget beside Resemble's: FLIP's mean error may be small but not this large.
  EXPECT_FALSE(aosuite::matches_golden(render(64, 48, 0.7f), GOLDENS "/disc.png",
                                       {.gates = {"flip.max_mean=0.001"}}));
}

TEST(Renderer, TheDefaultsPassJitterAndCatchAGlobalShift) {
  aosuite::Image a = render(64, 48), b = a;
  b.rgba[0] = static_cast<unsigned char>(b.rgba[0] + 3);           // one channel of one pixel
  EXPECT_TRUE(aosuite::compare(b, a));                             // within every default limit
  EXPECT_FALSE(aosuite::compare(render(64, 48, 0.6f, 1.02f), a));  // 2 % brighter: mean shift
}

TEST(Renderer, FloatFramesAreGatedByAFloatMetric) {
  aosuite::FloatFrame ao{8, 8, 1, std::vector<float>(64, 0.5f)}, darker = ao;
  darker.samples[9] = 0.45f;
  EXPECT_FALSE(aosuite::compare(darker, ao));  // no float gate: byte for byte
  EXPECT_TRUE(aosuite::compare(darker, ao, {.float_gates = {"rmse.max=0.01"}}));
  EXPECT_FALSE(aosuite::compare(darker, ao, {.float_gates = {"rmse.max=0.001"}}));
}

TEST(Renderer, AMissingGoldenIsNewAndSaysHowToWriteIt) {
  const aosuite::Verdict v = aosuite::matches_golden(render(8, 8), GOLDENS "/none/missing.png");
  EXPECT_EQ(v.status, aosuite::Verdict::Status::kNew) << v;
  EXPECT_NE(v.message.find("AOSUITE_UPDATE_GOLDENS=1"), std::string::npos) << v;
}

}  // namespace

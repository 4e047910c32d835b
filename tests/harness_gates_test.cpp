// Metric gates in a suite, as CI runs them: a case gated on FLIP for its final image and on
// RMSE for its float AO term (ao_float.exr), blessed, passing, then caught by a deliberate
// regression with each gate's value, limit and margin in results.json and the FLIP heat map
// in the report; Resemble's gate is off when only metric gates are given.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "broken_shaders.hpp"
#include "compare/opencv.hpp"
#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;
using test::read_text;

class HarnessGates : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "suites");
    test::write_broken_shaders(dir_ / "broken");
  }
  void suite(const std::string& tolerance, const std::string& images,
             const std::string& scene = "corner", const std::string& view = "inside") {
    std::ofstream(dir_ / "suites" / "g.toml") << R"(
[[case]]
scene = ")" << scene << R"("
views = [")" << view << R"("]
techniques = ["sao"]
width = 64
height = 36
images = )" << images << "\n[case.tolerance]\n"
                                              << tolerance;
  }
  test::Outcome aosuite(const std::string& args, const std::string& env = "") {
    return test::run_shell(
        "cd " + dir_.path().string() + " && " + env + " " + AOSUITE_BIN + " " + args, dir_.path());
  }
  std::string broken() const { return "AOSUITE_SHADER_DIR=" + (dir_ / "broken").string(); }
  nlohmann::json results() const {
    std::ifstream f(dir_ / "reports" / "g" / "results.json");
    return nlohmann::json::parse(f);
  }
  const fs::path case_dir = fs::path("corner-inside-sao-64x36");
  test::TempDir dir_;
};

TEST_F(HarnessGates, FlipAndAoFloatRmseGateACaseAndTheReportShowsTheHeatMap) {
  suite("flip = { max_mean = 0.01, max_q3 = 0.2 }\nrmse = { max = 0.01 }\n",
        R"(["with_ao", "ao_float"])");
  test::Outcome r = aosuite("bless suites/g.toml");
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "suites" / "goldens" / "g" / case_dir / "with_ao.png"));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "suites" / "goldens" / "g" / case_dir / "ao_float.exr"));
  r = aosuite("check suites/g.toml");
  ASSERT_EQ(r.rc, 0) << r.out << r.err;

  r = aosuite("check suites/g.toml", broken());
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("flip mean"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("rmse value"), std::string::npos) << r.out;
  const nlohmann::json c = results().at("cases").at(0);
  ASSERT_EQ(c.at("images").size(), 2u);
  for (const nlohmann::json& v : c.at("images")) {
    SCOPED_TRACE(v.dump());
    EXPECT_EQ(v.at("status"), "FAIL");
    ASSERT_FALSE(v.at("gates").empty());
    bool over = false;
    for (const nlohmann::json& g : v.at("gates")) {
      const double value = g.at("value"), limit = g.at("limit"), margin = g.at("margin");
      EXPECT_DOUBLE_EQ(margin, limit - value) << "max gates: margin = limit - value";
      EXPECT_EQ(g.at("pass").get<bool>(), margin >= 0);
      over |= !g.at("pass").get<bool>();
    }
    EXPECT_TRUE(over);
    EXPECT_TRUE(v.at("metrics").contains("flip") && v.at("metrics").contains("rmse"));
  }
  // The FLIP map of the failing final image, written into the report and shown by it.
  const std::string heat = c.at("files").at("heat:with_ao");
  const cv::Mat map = read_png_rgba8(dir_ / "reports" / "g" / "cases" / heat);
  EXPECT_EQ(map.cols, 64);
  EXPECT_NE(read_text(dir_ / "reports" / "g" / "index.html").find("heat_with_ao.png"),
            std::string::npos);
  EXPECT_NE(read_text(dir_ / "reports" / "g" / "index.html").find("FLIP error"), std::string::npos);

  // Approved from the report alone: the report knows its suite.
  r = aosuite("bless --failed --report reports/g");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("1 of 1 cases blessed"), std::string::npos) << r.out;
  r = aosuite("check suites/g.toml", broken());
  EXPECT_EQ(r.rc, 0) << "the report's images are the goldens now\n" << r.out;

  // Loose gates: the shaders as they are, against the regression's goldens, pass, for
  // Resemble's gate is lifted by name; and the changed tolerance is judged again, not reused.
  suite("resemble = false\nflip = { max_mean = 1 }\nrmse = { max = 1 }\n",
        R"(["with_ao", "ao_float"])");
  r = aosuite("check suites/g.toml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  // Without that, Resemble's gate holds beside them, and fails (the goldens are the
  // regression's now; the shaders as they are differ from them).
  suite("flip = { max_mean = 1 }\n", R"(["with_ao"])");
  r = aosuite("check suites/g.toml");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("mismatch"), std::string::npos) << r.out;
}

// The same regression judged over the frame and over geometry only: the background is the
// same in both images, so the counts agree and only the denominators differ.
TEST_F(HarnessGates, ForegroundOnlyMeasuresGeometryPixelsOnly) {
  const std::string images = R"(["with_ao"])";
  suite(
      "max_mismatch_percent = 100\nmax_channel_delta = 255\nmax_mean_shift = 255\nmax_mean_delta = "
      "255\nrmse = { max = 1 }\n",
      images, "spheres", "front");
  ASSERT_EQ(aosuite("bless suites/g.toml").rc, 0);
  ASSERT_EQ(aosuite("check suites/g.toml", broken()).rc, 0);
  const nlohmann::json frame = results().at("cases").at(0).at("images").at(0);
  suite(
      "max_mismatch_percent = 100\nmax_channel_delta = 255\nmax_mean_shift = 255\nmax_mean_delta = "
      "255\nrmse = { max = 1 }\nforeground_only = true\n",
      images, "spheres", "front");
  ASSERT_EQ(aosuite("check suites/g.toml", broken()).rc, 0);
  const nlohmann::json c = results().at("cases").at(0);
  const nlohmann::json geometry = c.at("images").at(0);
  const cv::Mat mask =
      read_png_rgba8(dir_ / "reports" / "g" / "cases" / c.at("files").at("foreground"));
  double fg = 0;
  for (int y = 0; y < mask.rows; ++y)
    for (int x = 0; x < mask.cols; ++x) fg += mask.at<cv::Vec4b>(y, x)[0] != 0;
  const double all = double(mask.total());
  ASSERT_GT(fg, 0.2 * all);
  ASSERT_LT(fg, 0.95 * all) << "the view must show some sky";
  EXPECT_NEAR(geometry.at("mismatch_percent").get<double>() * fg,
              frame.at("mismatch_percent").get<double>() * all, 1e-6 * all);
  const double rmse_frame = frame.at("metrics").at("rmse").at("value");
  const double rmse_geometry = geometry.at("metrics").at("rmse").at("value");
  ASSERT_GT(rmse_frame, 0);
  EXPECT_NEAR(rmse_geometry * rmse_geometry * fg, rmse_frame * rmse_frame * all, 1e-9 * all);
}

// Another renderer's float output, gated by a metric: folder mode's --gate, and an image case
// naming EXR files.
TEST_F(HarnessGates, EveryRenderersExrImagesAreGatedByMetrics) {
  for (const char* t : {"alchemy", "sao"}) {
    ASSERT_EQ(aosuite(std::string("render --scene corner --technique ") + t +
                      " --width 40 --height 30 --outputs ao_float --out " + t)
                  .rc,
              0);
  }
  fs::create_directories(dir_ / "actual"), fs::create_directories(dir_ / "expected");
  fs::copy_file(dir_ / "sao" / "corner_inside_sao_ao.exr", dir_ / "actual" / "ao.exr");
  fs::copy_file(dir_ / "alchemy" / "corner_inside_alchemy_ao.exr", dir_ / "expected" / "ao.exr");
  const std::string folders = "check --actual actual --expected expected --report rep";
  test::Outcome r = aosuite(folders + " --gate rmse.max=0.001");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("rmse value"), std::string::npos) << r.out;
  EXPECT_EQ(aosuite(folders + " --gate rmse.max=1 --gate ssim.min=0").rc, 0);
  r = aosuite(folders);
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.out.find("must hold the same samples, bit for bit"), std::string::npos) << r.out;
  EXPECT_EQ(aosuite("check suites/g.toml --gate rmse.max=1").rc, 2) << "a suite has its own";

  std::ofstream(dir_ / "suites" / "e.toml") << R"(
[[case]]
name = "float-ao"
files = ["../actual/ao.exr"]
[case.tolerance]
rmse = { max = 0.001 }
)";
  ASSERT_EQ(aosuite("bless suites/e.toml").rc, 0);
  EXPECT_TRUE(fs::is_regular_file(dir_ / "suites" / "goldens" / "e" / "float-ao" / "ao.exr"));
  EXPECT_EQ(aosuite("check suites/e.toml").rc, 0);
  fs::copy_file(dir_ / "expected" / "ao.exr", dir_ / "actual" / "ao.exr",
                fs::copy_options::overwrite_existing);
  r = aosuite("check suites/e.toml");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("rmse value"), std::string::npos) << r.out;
}

// Tolerance classes painted beside the golden: bless writes a blank map and keeps a painted
// one; a painted region's strict gate catches what the loose base gate allows.
TEST_F(HarnessGates, RegionMapsBesideTheGoldenPickTolerances) {
  suite(
      "resemble = false\nflip = { max_mean = 1 }\n[case.tolerance.regions]\n"
      "strict = { color = [255, 0, 0], flip = { max_mean = 0.001 } }\n",
      R"(["with_ao"])", "spheres", "front");
  ASSERT_EQ(aosuite("bless suites/g.toml").rc, 0);
  const fs::path golden_dir = dir_ / "suites" / "goldens" / "g" / "spheres-front-sao-64x36";
  const fs::path map = golden_dir / "with_ao.regions.png";
  ASSERT_TRUE(fs::is_regular_file(map));
  cv::Mat painted = read_png_rgba8(map);
  EXPECT_EQ(cv::countNonZero(painted.reshape(1) != cv::Scalar(0)), int(painted.total()))
      << "blank: black and opaque, every pixel unpainted";
  test::Outcome r = aosuite("check suites/g.toml", broken());
  EXPECT_EQ(r.rc, 0) << "nothing painted: the loose gate holds everywhere\n" << r.out;

  painted(cv::Rect(16, 10, 32, 20)).setTo(cv::Scalar(255, 0, 0, 255));
  write_png_rgba8(map, painted);
  r = aosuite("check suites/g.toml", broken());
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("strict: flip mean"), std::string::npos) << r.out;
  const nlohmann::json c = results().at("cases").at(0);
  bool strict = false;
  for (const auto& g : c.at("images").at(0).at("gates")) strict |= g.at("region") == "strict";
  EXPECT_TRUE(strict);
  EXPECT_TRUE(fs::is_regular_file(dir_ / "reports" / "g" / "cases" /
                                  c.at("files").at("regions:with_ao").get<std::string>()));
  // Blessing again keeps the painted map.
  ASSERT_EQ(aosuite("bless suites/g.toml --force", broken()).rc, 0);
  EXPECT_EQ(cv::norm(read_png_rgba8(map), painted, cv::NORM_INF), 0.0);

  painted.at<cv::Vec4b>(0, 0) = {1, 2, 3, 255};
  write_png_rgba8(map, painted);
  r = aosuite("check suites/g.toml");
  EXPECT_EQ(r.rc, 2) << r.out;
  EXPECT_NE(r.out.find("no region's colour"), std::string::npos) << r.out;
  fs::remove(map);
  r = aosuite("check suites/g.toml");
  EXPECT_EQ(r.rc, 2) << r.out;
  EXPECT_NE(r.out.find("no region map"), std::string::npos) << r.out;
}

TEST_F(HarnessGates, BadGatesAreSuiteErrors) {
  struct Bad {
    std::string tolerance, images, message;
  };
  const Bad cases[] = {
      {"rmse = { max = 0.01 }\n", R"(["ao_float", "nope"])", "unknown image 'nope'"},
      {"max_mismatch_percent = 1\n", R"(["ao_float"])", "ao_float is judged by metric gates only"},
      {"flip = { max_nope = 1 }\n", R"(["with_ao"])", "flip has no gate 'max_nope'"},
      {"flip = { }\n", R"(["with_ao"])", "flip sets no limit"},
      {"ssimm = { min = 0.9 }\n", R"(["with_ao"])", "unknown key 'ssimm'"},
      {"flip = { max = \"big\" }\n", R"(["with_ao"])", "g.toml:"},
      {"[case.tolerance.regions]\nsky = { color = [0, 0, 0], flip = { max = 1 } }\n",
       R"(["with_ao"])", "black marks unclassified"},
      {"[case.tolerance.regions]\nsky = { color = [9, 9, 9] }\n", R"(["with_ao"])",
       "region 'sky' has no metric gate"},
  };
  for (const Bad& bad : cases) {
    SCOPED_TRACE(bad.tolerance);
    suite(bad.tolerance, bad.images);
    const test::Outcome r = aosuite("check suites/g.toml");
    EXPECT_EQ(r.rc, 2) << r.out;
    EXPECT_NE(r.err.find(bad.message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "reports" / "g" / "results.json"));
  }
}

}  // namespace
}  // namespace aosuite

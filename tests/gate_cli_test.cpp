// Gates end to end through the CLI. The warning tier (`[tolerance.warn]`, folder mode's
// --warn-max-mismatch and --warn-gate): an image inside the failing limits but beyond a warning
// limit is a WARN that exits 0, in the terminal, results.json, JUnit and the report, and is
// accepted as a failure is; beyond the failing limits it still fails. And where an image
// differs most (idiff's "max error @ (x, y)"), for 8-bit and float images.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "compare/opencv.hpp"
#include "exr_fixture.hpp"
#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;
using test::read_text;

class GateCli : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_ / "s"); }
  // x.png: 8x6 grey with its first `pixels` pixels' red raised by `delta`.
  void draw(const fs::path& file, int pixels, int delta) {
    cv::Mat m(6, 8, CV_8UC4, cv::Scalar(100, 100, 100, 255));
    for (int i = 0; i < pixels; ++i) m.at<cv::Vec4b>(i / 8, i % 8)[0] = std::uint8_t(100 + delta);
    fs::create_directories(file.parent_path());
    write_png_rgba8(file, m);
  }
  void suite(const std::string& tolerance) {
    std::ofstream(dir_ / "s" / "w.toml", std::ios::trunc)
        << "[[case]]\nname = \"x\"\nfiles = [\"x.png\"]\n[case.tolerance]\n"
        << tolerance;
  }
  test::Outcome aosuite(const std::string& args) {
    return test::run_shell("cd " + dir_.path().string() + " && " + AOSUITE_BIN + " " + args,
                           dir_.path());
  }
  nlohmann::json results() const {
    return nlohmann::json::parse(read_text(dir_ / "reports" / "w" / "results.json"));
  }
  test::TempDir dir_;
};

// One pixel of 48 changed (2.08 %): inside the failing 10 %, beyond the warning 1 %.
TEST_F(GateCli, AnImageBeyondAWarningLimitPassesWithAWarnStatus) {
  const std::string tolerance =
      "max_mismatch_percent = 10\nmax_channel_delta = 255\nmax_mean_shift = 255\nmax_mean_delta = "
      "255\nwarn = { max_mismatch_percent = 1 }\n";
  suite(tolerance);
  draw(dir_ / "s" / "x.png", 0, 0);
  ASSERT_EQ(aosuite("bless s/w.toml").rc, 0);
  draw(dir_ / "s" / "x.png", 1, 50);
  test::Outcome r = aosuite("check s/w.toml --junit junit.xml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("WARN  x"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("warning: mismatch 2.08% (allowed 1%)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 case: 0 passed, 0 failed, 0 new, 0 errors, 1 with warnings"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("to accept x: "), std::string::npos) << r.out;
  const nlohmann::json c = results().at("cases").at(0);
  EXPECT_EQ(c.at("status"), "WARN");
  EXPECT_EQ(c.at("images").at(0).at("status"), "WARN");
  EXPECT_EQ(c.at("tolerance").at("warn").at("max_mismatch_percent"), 1.0);
  const std::string junit = read_text(dir_ / "junit.xml");
  EXPECT_NE(junit.find("<system-out>WARN: x: warning: mismatch 2.08%"), std::string::npos) << junit;
  EXPECT_EQ(junit.find("<failure"), std::string::npos) << junit;
  const std::string page = read_text(dir_ / "reports" / "w" / "index.html");
  EXPECT_NE(page.find("<span class=WARN>1 with warnings</span>"), std::string::npos);
  EXPECT_NE(page.find("data-status=WARN checked> WARN (1)"), std::string::npos);

  // Six pixels (12.5 %) are beyond the failing limit: a failure, whatever the warning says.
  draw(dir_ / "s" / "x.png", 6, 50);
  r = aosuite("check s/w.toml");
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_EQ(results().at("cases").at(0).at("status"), "FAIL");

  // Without the warning tier the one-pixel change is a plain pass.
  suite(
      "max_mismatch_percent = 10\nmax_channel_delta = 255\nmax_mean_shift = 255\nmax_mean_delta = "
      "255\n");
  draw(dir_ / "s" / "x.png", 1, 50);
  r = aosuite("check s/w.toml");
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_EQ(results().at("cases").at(0).at("status"), "PASS");

  // Accepting a warning makes the new image the golden, as for a failure, from the report's
  // images with `--failed` too.
  suite(tolerance);
  ASSERT_EQ(aosuite("check s/w.toml").rc, 0);
  r = aosuite("bless s/w.toml --failed --report reports/w");
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(read_file(dir_ / "s" / "goldens" / "w" / "x" / "x.png"),
            read_file(dir_ / "s" / "x.png"));
  r = aosuite("check s/w.toml");
  EXPECT_EQ(r.rc, 0);
  EXPECT_EQ(results().at("cases").at(0).at("status"), "PASS");
}

// A metric that only the warning tier gates is measured for it, and its gate warns.
TEST_F(GateCli, AMetricOnlyTheWarningTierGatesIsMeasuredAndWarns) {
  suite(
      "max_mismatch_percent = 100\nmax_channel_delta = 255\nmax_mean_shift = 255\nmax_mean_delta = "
      "255\n[case.tolerance.warn]\nrmse = { max = 0.001 }\n");
  draw(dir_ / "s" / "x.png", 0, 0);
  ASSERT_EQ(aosuite("bless s/w.toml").rc, 0);
  draw(dir_ / "s" / "x.png", 3, 20);
  test::Outcome r = aosuite("check s/w.toml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  const nlohmann::json image = results().at("cases").at(0).at("images").at(0);
  EXPECT_EQ(image.at("status"), "WARN");
  EXPECT_TRUE(image.at("metrics").contains("rmse")) << image;
  EXPECT_NE(image.at("message").get<std::string>().find("warning: rmse"), std::string::npos)
      << image;
  // The failing tier's outcomes alone are the image's gates: none here.
  EXPECT_TRUE(image.at("gates").empty()) << image;
}

TEST_F(GateCli, FolderModeWarnsFromTheCommandLine) {
  draw(dir_ / "exp" / "a.png", 0, 0);
  draw(dir_ / "act" / "a.png", 1, 50);
  test::Outcome r = aosuite(
      "check --actual act --expected exp --max-mismatch 10 --max-channel-delta 255 --limit "
      "max_mean_shift=255 --limit max_mean_delta=255 --warn-max-mismatch 1");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("WARN "), std::string::npos) << r.out;
  r = aosuite(
      "check --actual act --expected exp --max-mismatch 10 --max-channel-delta 255 --limit "
      "max_mean_shift=255 --limit max_mean_delta=255 --warn-gate flip.max_mean=1");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(r.out.find("WARN "), std::string::npos) << r.out;
  r = aosuite(
      "check --actual act --expected exp --max-mismatch 10 --max-channel-delta 255 --limit "
      "max_mean_shift=255 --limit max_mean_delta=255 --warn-gate flip.max_mean=0.00001");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("warning: flip mean"), std::string::npos) << r.out;
  r = aosuite("check --actual act --expected exp --gate flip.max_mean=0.00001");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
}

TEST_F(GateCli, BadWarningTiersAreSuiteErrors) {
  draw(dir_ / "s" / "x.png", 0, 0);
  suite("warn = {}\n");
  test::Outcome r = aosuite("check s/w.toml");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("[tolerance.warn] sets no limit"), std::string::npos) << r.err;
  suite("warn = { nope = 1 }\n");
  r = aosuite("check s/w.toml");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("unknown key 'nope' (warn keys: max_mismatch_percent"), std::string::npos)
      << r.err;
  suite("warn = { max_mismatch_percent = 100 }\n");
  r = aosuite("check s/w.toml");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("warn.max_mismatch_percent must be 0..100 (below 100)"), std::string::npos)
      << r.err;
}

// The largest difference and the first pixel that holds it, in the terminal line, results.json
// and the report's data: 8-bit images in channel levels, float ones in their own unit.
TEST_F(GateCli, TheLargestDifferenceIsLocated) {
  cv::Mat golden(6, 8, CV_8UC4, cv::Scalar(100, 100, 100, 255)), changed = golden.clone();
  changed.at<cv::Vec4b>(1, 1)[1] = 110;
  changed.at<cv::Vec4b>(2, 5)[2] = 140;  // the largest, at (5, 2)
  changed.at<cv::Vec4b>(4, 7)[0] = 140;  // as large, later: not named
  fs::create_directories(dir_ / "exp");
  fs::create_directories(dir_ / "act");
  write_png_rgba8(dir_ / "exp" / "a.png", golden);
  write_png_rgba8(dir_ / "act" / "a.png", changed);
  std::vector<float> grey(48, 0.5f), moved = grey;
  moved[3 * 8 + 6] = 0.75f;  // (6, 3)
  moved[10] = 0.625f;
  test::write_exr(dir_ / "exp" / "f.exr", 8, 6, {"Y"}, grey);
  test::write_exr(dir_ / "act" / "f.exr", 8, 6, {"Y"}, moved);
  test::Outcome r = aosuite(
      "check --actual act --expected exp --gate rmse.max=1 --max-mismatch 100 "
      "--max-channel-delta 255 --limit max_mean_shift=255 --limit max_mean_delta=255 "
      "--report rep");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("max Δ 40 @ (5, 2)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("max Δ 0.25 @ (6, 3)"), std::string::npos) << r.out;
  const nlohmann::json cases =
      nlohmann::json::parse(read_text(dir_ / "rep" / "results.json")).at("cases");
  ASSERT_EQ(cases.size(), 2u);
  for (const nlohmann::json& c : cases) {
    const nlohmann::json largest = c.at("images").at(0).at("largest");
    const bool png = c.at("source").get<std::string>().ends_with(".png");
    EXPECT_EQ(largest.at("value"), png ? 40.0 : 0.25) << c;
    EXPECT_EQ(largest.at("x"), png ? 5 : 6) << c;
    EXPECT_EQ(largest.at("y"), png ? 2 : 3) << c;
  }
  EXPECT_NE(read_text(dir_ / "rep" / "index.html").find("40 @ (5, 2)"), std::string::npos);
}

}  // namespace
}  // namespace aosuite

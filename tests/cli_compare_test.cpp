// `aosuite compare` as a user runs it: exit codes, messages, and nothing written on error.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "compare/opencv.hpp"
#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

using test::Outcome;

Outcome run(const test::TempDir& dir, const std::string& args) {
  return test::run_shell(std::string(AOSUITE_BIN) + " compare " + args, dir.path());
}

class CliCompare : public ::testing::Test {
 protected:
  void SetUp() override {
    cv::Mat a(20, 30, CV_8UC4, cv::Scalar(10, 20, 30, 255));
    write_png_rgba8(dir_ / "a.png", a);
    write_png_rgba8(dir_ / "a_copy.png", a);
    a.at<cv::Vec4b>(5, 7) = cv::Vec4b(200, 20, 30, 255);
    write_png_rgba8(dir_ / "b.png", a);
    write_png_rgba8(dir_ / "small.png", cv::Mat(10, 10, CV_8UC4, cv::Scalar::all(255)));
  }
  std::string path(const char* name) const { return (dir_ / name).string(); }
  test::TempDir dir_;
};

TEST_F(CliCompare, SameIsZeroDifferentIsOne) {
  EXPECT_EQ(run(dir_, path("a.png") + " " + path("a_copy.png")).rc, 0);
  EXPECT_EQ(run(dir_, path("a.png") + " " + path("a.png")).rc, 0);
  const Outcome r = run(dir_, path("a.png") + " " + path("b.png"));
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.out.find("different"), std::string::npos);
  // one pixel of 600 is 0.1666 %: within a 0.2 % threshold
  EXPECT_EQ(run(dir_, path("a.png") + " " + path("b.png") + " --threshold 0.2").rc, 0);
  EXPECT_EQ(run(dir_, path("a.png") + " " + path("small.png") + " --threshold 100").rc, 1);
}

TEST_F(CliCompare, JsonHasResemblesKeysInOrder) {
  const Outcome r = run(dir_, path("a.png") + " " + path("b.png") + " --json");
  const auto j = nlohmann::ordered_json::parse(r.out);
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"misMatchPercentage", "rawMisMatchPercentage",
                                            "isSameDimensions", "dimensionDifference", "diffBounds",
                                            "analysisTime"}));
  EXPECT_EQ(j["misMatchPercentage"], "0.17");
  EXPECT_EQ(j["diffBounds"].dump(), R"({"top":5,"left":7,"bottom":5,"right":7})");
}

TEST_F(CliCompare, WritesDiffOnlyWhenAsked) {
  EXPECT_EQ(run(dir_, path("a.png") + " " + path("b.png") + " --diff " + path("d.png")).rc, 1);
  const cv::Mat d = read_png_rgba8(dir_ / "d.png");
  EXPECT_EQ(d.at<cv::Vec4b>(5, 7), cv::Vec4b(255, 0, 255, 255));
  EXPECT_EQ(d.at<cv::Vec4b>(0, 0), cv::Vec4b(10, 20, 30, 255));
}

TEST_F(CliCompare, BadInputIsExitTwoWithOneLineAndNothingWritten) {
  test::write_bytes(dir_ / "text.png", {'n', 'o', 'p', 'e'});
  const auto good = read_file(dir_ / "a.png");
  test::write_bytes(dir_ / "cut.png", test::Bytes(good.begin(), good.begin() + 60));
  test::write_bytes(dir_ / "huge.png", test::make_png(100000, 100000, 8, 6, {}));
  for (const char* bad : {"missing.png", "text.png", "cut.png", "huge.png"}) {
    const Outcome r = run(dir_, path("a.png") + " " + path(bad) + " --diff " + path("out.png"));
    EXPECT_EQ(r.rc, 2) << bad;
    EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "out.png")) << bad;
  }
  // Byte-identical files skip the pixel comparison, but not the check that they decode.
  test::Bytes bad_data = good;
  bad_data[good.size() - 20] ^= 0x55;  // in the last IDAT: its CRC no longer matches
  test::write_bytes(dir_ / "bad_data.png", bad_data);
  for (const char* bad : {"text.png", "cut.png", "huge.png", "bad_data.png"}) {
    const Outcome r = run(dir_, path(bad) + " " + path(bad));
    EXPECT_EQ(r.rc, 2) << bad << " against itself";
    EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
  }
  EXPECT_EQ(run(dir_, path("a.png") + " " + path("b.png") + " --mode sideways").rc, 2);
  EXPECT_EQ(run(dir_, path("a.png")).rc, 2);
}

TEST_F(CliCompare, BatchReadsOracleFormat) {
  std::ofstream(dir_ / "pairs.txt")
      << "# comment\n"
      << path("a.png") << "\t" << path("b.png") << "\n"
      << R"({"id":"x","a":")" << path("a.png") << R"(","b":")" << path("b.png")
      << R"(","mode":"colors"})"
      << "\n"
      << R"({"a":")" << path("a.png") << R"(","b":")" << path("missing.png") << R"("})"
      << "\n";
  const Outcome r = run(dir_, "--batch " + path("pairs.txt"));
  EXPECT_EQ(r.rc, 2);
  std::istringstream lines(r.out);
  std::string l1, l2, l3;
  std::getline(lines, l1), std::getline(lines, l2), std::getline(lines, l3);
  EXPECT_EQ(nlohmann::json::parse(l1)["misMatchPercentage"], "0.17");
  EXPECT_EQ(nlohmann::json::parse(l2)["id"], "x");
  EXPECT_EQ(nlohmann::json::parse(l2)["misMatchPercentage"], "0.17");  // red 200 vs 10: brighter
  EXPECT_TRUE(nlohmann::json::parse(l3).contains("error"));
}

}  // namespace
}  // namespace aosuite

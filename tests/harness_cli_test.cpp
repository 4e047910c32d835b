// `aosuite check`, `bless` and `report merge` as CI runs them: exit codes, goldens only
// replaced when asked and never half-written, a changed shader caught and its report readable
// in a real browser.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "compare/opencv.hpp"
#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::stringstream s;
  s << std::ifstream(p).rdbuf();
  return s.str();
}

class HarnessCli : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "suites");
    std::ofstream(dir_ / "suites" / "t.toml") << R"(
[defaults]
width = 48
height = 27
techniques = ["alchemy", "sao"]
[defaults.tolerance]
mode = "less"
max_mismatch_percent = 0.5

[[case]]
scene = "corner"
)";
    // A copy of the shaders with SAO twice as dark: a deliberate regression.
    fs::copy(fs::path(AOSUITE_SOURCE_DIR) / "renderer" / "shaders", dir_ / "broken");
    std::string sao = read_text(dir_ / "broken" / "sao.frag");
    const std::string term = "1.0 - sum * u_intensity";
    ASSERT_NE(sao.find(term), std::string::npos) << "sao.frag changed; update this test";
    sao.replace(sao.find(term), term.size(), "1.0 - 2.0 * sum * u_intensity");
    std::ofstream(dir_ / "broken" / "sao.frag") << sao;
  }
  test::Outcome aosuite(const std::string& args, const std::string& env = "") {
    return test::run_shell(
        "cd " + dir_.path().string() + " && " + env + " " + AOSUITE_BIN + " " + args, dir_.path());
  }
  std::string broken() const { return "AOSUITE_SHADER_DIR=" + (dir_ / "broken").string(); }
  std::map<fs::path, std::vector<unsigned char>> goldens() const {
    std::map<fs::path, std::vector<unsigned char>> out;
    for (const auto& e : fs::recursive_directory_iterator(dir_ / "goldens")) {
      if (e.is_regular_file()) out[e.path()] = read_file(e.path());
    }
    return out;
  }
  test::TempDir dir_;
};

TEST_F(HarnessCli, NewThenBlessedThenPassingThenReused) {
  test::Outcome r = aosuite("check suites/t.toml --junit junit.xml");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;  // no goldens yet: new, not passing
  EXPECT_NE(r.out.find("4 new"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("aosuite bless suites/t.toml --filter '^corner-"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "goldens"));  // check never writes goldens
  EXPECT_NE(read_text(dir_ / "junit.xml").find("failures=\"4\""), std::string::npos);

  r = aosuite("bless suites/t.toml --filter sao");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(goldens().size(), 2u);  // only the filtered cases
  r = aosuite("bless suites/t.toml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(goldens().size(), 4u);
  for (const auto& [path, bytes] : goldens()) EXPECT_EQ(path.filename(), "with_ao.png");

  // Two render threads, two GL contexts: the same verdicts as one.
  r = aosuite("check suites/t.toml --junit junit.xml --jobs 2 --no-reuse");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("4 passed"), std::string::npos) << r.out;
  EXPECT_NE(read_text(dir_ / "junit.xml").find("tests=\"4\" failures=\"0\" errors=\"0\""),
            std::string::npos);
  r = aosuite("check suites/t.toml");
  EXPECT_EQ(r.rc, 0);
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 5) << r.out;  // 4 cases + summary
  std::size_t reused = 0;
  for (std::size_t at = 0; (at = r.out.find("(unchanged, reused)", at)) != std::string::npos; ++at)
    ++reused;
  EXPECT_EQ(reused, 4u) << r.out;
}

TEST_F(HarnessCli, ChangedShaderFailsWithAReadableReportAndBlessMakesItPass) {
  ASSERT_EQ(aosuite("bless suites/t.toml").rc, 0);
  const auto before = goldens();
  test::Outcome r = aosuite("check suites/t.toml", broken());
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("2 passed, 2 failed"), std::string::npos) << r.out;  // the SAO cases
  EXPECT_EQ(goldens(), before);  // a failing check touches no golden

  // The page as a person sees it: load it in headless Chromium, let its script run.
  const fs::path page = dir_ / "reports" / "t" / "index.html";
  r = test::run_shell(
      "chromium --headless --no-sandbox --disable-gpu --dump-dom file://" + page.string(),
      dir_.path());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("corner-inside-sao-48x27"), std::string::npos);
  EXPECT_NE(r.out.find("class=\"FAIL\""), std::string::npos);
  EXPECT_NE(r.out.find("aosuite bless suites/t.toml --filter '^corner-inside-sao-48x27$'"),
            std::string::npos);
  EXPECT_NE(r.out.find("src=\"data:image/png;base64,iVBOR"), std::string::npos);  // images filled
  EXPECT_EQ(r.out.find("data-key=\"\""), std::string::npos);
  EXPECT_NE(r.out.find("class=\"slider\""), std::string::npos);
  r = test::run_shell(
      "chromium --headless --no-sandbox --disable-gpu --window-size=1000,1400 "
      "--screenshot=" +
          (dir_ / "shot.png").string() + " file://" + page.string(),
      dir_.path());
  ASSERT_EQ(r.rc, 0) << r.err;
  const cv::Mat shot = read_png_rgba8(dir_ / "shot.png");
  EXPECT_EQ(shot.cols, 1000);
  cv::Scalar mean, stddev;
  cv::meanStdDev(shot, mean, stddev);
  EXPECT_GT(stddev[0], 10) << "the screenshot is blank";

  r = aosuite("bless suites/t.toml --filter sao", broken());
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(aosuite("check suites/t.toml", broken()).rc, 0);
  EXPECT_EQ(aosuite("check suites/t.toml").rc, 1);  // the goldens now hold the changed look
}

TEST_F(HarnessCli, ShardsMergeIntoOneReport) {
  ASSERT_EQ(aosuite("bless suites/t.toml").rc, 0);
  EXPECT_EQ(aosuite("check suites/t.toml --shard 0/2 --report a").rc, 0);
  EXPECT_EQ(aosuite("check suites/t.toml --report b",
                    "GTEST_SHARD_INDEX=1 GTEST_TOTAL_SHARDS=2 "
                    "GTEST_SHARD_STATUS_FILE=" +
                        (dir_ / "ack").string())
                .rc,
            0);
  EXPECT_TRUE(fs::exists(dir_ / "ack"));  // the sharding protocol is acknowledged
  const auto a = nlohmann::json::parse(read_text(dir_ / "a" / "results.json"));
  const auto b = nlohmann::json::parse(read_text(dir_ / "b" / "results.json"));
  EXPECT_EQ(a["cases"].size() + b["cases"].size(), 4u);
  EXPECT_EQ(a["shard"], "0/2");
  const test::Outcome r = aosuite("report merge --out m a b --junit m/junit.xml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(nlohmann::json::parse(read_text(dir_ / "m" / "results.json"))["cases"].size(), 4u);
  const std::string html = read_text(dir_ / "m" / "index.html");
  for (const char* id : {"corner-inside-alchemy-48x27", "corner-front-sao-48x27"}) {
    EXPECT_NE(html.find(id), std::string::npos) << id;
  }
  EXPECT_TRUE(fs::exists(dir_ / "m" / "cases" / "corner-front-sao-48x27" / "with_ao.png"));
}

TEST_F(HarnessCli, BadInputIsAClearErrorAndLosesNothing) {
  test::Outcome r = aosuite("check suites/missing.toml");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("missing.toml"), std::string::npos) << r.err;

  std::ofstream(dir_ / "suites" / "bad.toml") << "[[case]]\nscene = \"atlantis\"\n";
  r = aosuite("check suites/bad.toml");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("suites/bad.toml:2:"), std::string::npos) << r.err;

  ASSERT_EQ(aosuite("bless suites/t.toml").rc, 0);
  std::ofstream(dir_ / "notadir") << "x";
  r = aosuite("check suites/t.toml --report notadir/sub");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("notadir"), std::string::npos) << r.err;

  const fs::path golden = dir_ / "goldens" / "t" / "corner-inside-sao-48x27" / "with_ao.png";
  std::ofstream(golden, std::ios::trunc) << "garbage";
  r = aosuite("check suites/t.toml");
  EXPECT_EQ(r.rc, 2) << r.out;  // an unreadable golden cannot be judged
  EXPECT_NE(r.out.find("ERROR corner-inside-sao-48x27"), std::string::npos) << r.out;

  write_png_rgba8(golden, cv::Mat(10, 10, CV_8UC4, cv::Scalar(0, 0, 0, 255)));
  r = aosuite("check suites/t.toml");
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_NE(r.out.find("golden is 10x10, render is 48x27"), std::string::npos) << r.out;
  fs::remove(golden);
  r = aosuite("check suites/t.toml");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.out.find("NEW   corner-inside-sao-48x27"), std::string::npos) << r.out;
}

// A bless killed at any moment leaves every golden whole: the old file or the new one.
TEST_F(HarnessCli, KilledBlessLeavesEveryGoldenWhole) {
  std::ofstream(dir_ / "suites" / "t.toml", std::ios::app) << "[[case]]\nscene = \"village\"\n"
                                                              "width = 480\nheight = 270\n";
  ASSERT_EQ(aosuite("bless suites/t.toml").rc, 0);
  const auto before = goldens();
  for (int delay_ms : {150, 500, 900, 1300}) {
    const std::string pid_file = (dir_ / "pid").string();
    std::system(("cd " + dir_.path().string() + " && (" + broken() + " exec " + AOSUITE_BIN +
                 " bless suites/t.toml --no-reuse >/dev/null 2>&1 & echo $! > " + pid_file + ")")
                    .c_str());
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    const pid_t pid = std::stoi(read_text(pid_file));
    kill(pid, SIGKILL);
    while (kill(pid, 0) == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const auto after = goldens();
    int replaced = 0;
    for (const auto& [path, bytes] : before) {
      ASSERT_TRUE(after.contains(path)) << path << " lost after a kill at " << delay_ms << " ms";
      if (after.at(path) != bytes) {
        ++replaced;
        EXPECT_NO_THROW(decode_png_rgba8(after.at(path), path.string())) << delay_ms << " ms";
      }
    }
    for (const auto& [path, bytes] : after) {
      // A temporary caught before its rename is a dot-file, which golden lookup ignores.
      const bool hidden = path.filename().string().starts_with(".");
      EXPECT_TRUE(before.contains(path) || hidden) << "stray file " << path;
    }
    std::printf("killed after %d ms: %d of %zu goldens replaced\n", delay_ms, replaced,
                before.size());
  }
}

}  // namespace
}  // namespace aosuite

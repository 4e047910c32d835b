// `aosuite check`, `bless` and `report merge` as CI runs them: exit codes, goldens only
// replaced when asked and never half-written, a changed shader caught and its report readable
// in a real browser.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>

#include "broken_shaders.hpp"
#include "compare/opencv.hpp"
#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;

using test::read_text;

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
    test::write_broken_shaders(dir_ / "broken");
  }
  test::Outcome aosuite(const std::string& args, const std::string& env = "") {
    return test::run_shell(
        "cd " + dir_.path().string() + " && " + env + " " + AOSUITE_BIN + " " + args, dir_.path());
  }
  std::string broken() const { return "AOSUITE_SHADER_DIR=" + (dir_ / "broken").string(); }
  // The goldens beside a suite in `folder` (goldens/<name>).
  std::map<fs::path, std::vector<unsigned char>> goldens(
      const std::string& folder = "suites") const {
    std::map<fs::path, std::vector<unsigned char>> out;
    for (const auto& e : fs::recursive_directory_iterator(dir_ / folder / "goldens")) {
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
  EXPECT_FALSE(fs::exists(dir_ / "suites" / "goldens"));  // check never writes goldens
  EXPECT_NE(read_text(dir_ / "junit.xml").find("failures=\"4\""), std::string::npos);

  r = aosuite("bless suites/t.toml --filter sao");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(goldens().size(), 4u);  // only the filtered cases: each golden and its pass record
  r = aosuite("bless suites/t.toml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(goldens().size(), 8u);
  for (const auto& [path, bytes] : goldens()) {
    EXPECT_TRUE(path.filename() == "with_ao.png" || path.filename() == "with_ao.passes.json")
        << path;
  }

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
  // One file with every image embedded: the form to mail or attach.
  test::Outcome r = aosuite("check suites/t.toml --single-file", broken());
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("2 passed, 2 failed"), std::string::npos) << r.out;  // the SAO cases
  // The first pass that differs from the golden's, from the hashes bless kept beside it.
  EXPECT_NE(r.out.find("; ao differs (gbuffer identical)"), std::string::npos) << r.out;
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

  // A shard missing is refused, naming it, and writes nothing; --partial merges and says so.
  test::Outcome p = aosuite("report merge --out p a");
  EXPECT_EQ(p.rc, 2) << p.out << p.err;
  EXPECT_NE(p.err.find("shard 1/2 of the run is missing"), std::string::npos) << p.err;
  EXPECT_FALSE(fs::exists(dir_ / "p"));
  p = aosuite("report merge --out p a a");
  EXPECT_EQ(p.rc, 2) << p.out << p.err;
  EXPECT_NE(p.err.find("a: shard 0/2 is given twice"), std::string::npos) << p.err;
  p = aosuite("report merge --out p a --partial");
  EXPECT_EQ(p.rc, 0) << p.out << p.err;
  EXPECT_NE(p.err.find("a partial run: 1/2 missing"), std::string::npos) << p.err;
  const auto part = nlohmann::json::parse(read_text(dir_ / "p" / "results.json"));
  EXPECT_EQ(part["shard"], "partial, missing 1/2");
  EXPECT_EQ(part["cases"].size(), a["cases"].size());
  EXPECT_NE(read_text(dir_ / "p" / "index.html").find("partial, missing 1/2"), std::string::npos);
  // The first shard missing is named as well as the last.
  p = aosuite("report merge --out q b");
  EXPECT_EQ(p.rc, 2) << p.out << p.err;
  EXPECT_NE(p.err.find("shard 0/2 of the run is missing"), std::string::npos) << p.err;
  // --out naming a shard would overwrite it: refused.
  p = aosuite("report merge --out ./a a b");
  EXPECT_EQ(p.rc, 2) << p.out << p.err;
  EXPECT_NE(p.err.find("--out ./a is the shard a"), std::string::npos) << p.err;
  // A shard's image that is a link is refused by name, and nothing is merged.
  const fs::path linked =
      dir_ / "b" / "cases" / b["cases"][0]["id"].get<std::string>() / "with_ao.png";
  ASSERT_TRUE(fs::exists(linked));
  fs::remove(linked);
  fs::create_symlink(dir_ / "suites" / "t.toml", linked);
  p = aosuite("report merge --out q a b");
  EXPECT_EQ(p.rc, 2) << p.out << p.err;
  EXPECT_NE(p.err.find("with_ao.png: a link or special file in a shard's report"),
            std::string::npos)
      << p.err;
  EXPECT_FALSE(fs::exists(dir_ / "q"));
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

  const fs::path golden =
      dir_ / "suites" / "goldens" / "t" / "corner-inside-sao-48x27" / "with_ao.png";
  std::ofstream(golden, std::ios::trunc) << "garbage";
  r = aosuite("check suites/t.toml");
  EXPECT_EQ(r.rc, 2) << r.out;  // an unreadable golden cannot be judged
  EXPECT_NE(r.out.find("ERROR corner-inside-sao-48x27"), std::string::npos) << r.out;

  write_png_rgba8(golden, cv::Mat(10, 10, CV_8UC4, cv::Scalar(0, 0, 0, 255)));
  r = aosuite("check suites/t.toml");
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_NE(r.out.find("expected is 10x10, actual is 48x27"), std::string::npos) << r.out;
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
        if (path.extension() == ".png") {  // else a pass record (JSON), whole as well
          EXPECT_NO_THROW(decode_png_rgba8(after.at(path), path.string())) << delay_ms << " ms";
        } else {
          EXPECT_TRUE(nlohmann::json::accept(after.at(path))) << path;
        }
      }
    }
    for (const auto& [path, bytes] : after) {
      // A temporary caught before its rename is a dot-file, or a file in a case's dot-folder
      // staged beside it (replace_case_goldens), which golden lookup ignores.
      const bool hidden =
          std::ranges::any_of(path.lexically_relative(dir_ / "suites" / "goldens"),
                              [](const fs::path& part) { return part.string().starts_with("."); });
      EXPECT_TRUE(before.contains(path) || hidden) << "stray file " << path;
    }
    std::printf("killed after %d ms: %d of %zu goldens replaced\n", delay_ms, replaced,
                before.size());
  }
}

// A view that draws no geometry is never a silent pass: render warns, a suite case is an ERROR
// saying why, unless the case says allow_empty = true.
TEST_F(HarnessCli, AnEmptyViewIsNeverASilentPass) {
  std::ofstream(dir_ / "suites" / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir_ / "suites" / "away.toml") << R"([[meshes]]
file = "tri.obj"
[[views]]
name = "away"
eye = [0, 0, 3]
target = [0, 0, 6]
)";
  std::ofstream(dir_ / "suites" / "e.toml") << R"(
[defaults]
width = 16
height = 9
techniques = ["sao"]
[[case]]
scene = "away.toml"
[[case]]
scene = "away.toml"
name = "expected"
allow_empty = true
)";
  test::Outcome r = aosuite("check suites/e.toml");
  EXPECT_EQ(r.rc, 2) << r.out;
  EXPECT_NE(r.out.find("ERROR away-away-sao-16x9  view 'away' draws no geometry"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("NEW   away-away-sao-16x9-expected"), std::string::npos) << r.out;
  r = aosuite("render --scene suites/away.toml --width 16 --height 9 --out rendered");
  EXPECT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.err.find("warning: view 'away' of"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("draws no geometry"), std::string::npos) << r.err;
  std::ofstream(dir_ / "suites" / "g.toml") << R"(name = "g"
scenes = ["away.toml"]
resolutions = [[32, 18]]
runs = 1
rays = 4
[techniques.sao]
samples = [4]
radius = [1, 2]
)";
  r = aosuite("sweep suites/g.toml --out swept");
  EXPECT_EQ(r.rc, 0) << r.err;
  const std::string warning = "warning: view 'away' of away draws no geometry";
  ASSERT_NE(r.err.find(warning), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(warning), r.err.rfind(warning)) << "once per view, not per row: " << r.err;
}

// A run that judges nothing is never green, and leaves the last report as it was.
TEST_F(HarnessCli, AnEmptySelectionIsAnErrorAndKeepsTheLastReport) {
  ASSERT_EQ(aosuite("bless suites/t.toml").rc, 0);
  ASSERT_EQ(aosuite("check suites/t.toml --junit junit.xml").rc, 0);
  const std::string index = read_text(dir_ / "reports" / "t" / "index.html");
  const std::string results = read_text(dir_ / "reports" / "t" / "results.json");
  const auto before = goldens();
  for (const char* command : {"check suites/t.toml --filter nomatch --junit junit.xml",
                              "bless suites/t.toml --filter nomatch"}) {
    const test::Outcome r = aosuite(command);
    EXPECT_EQ(r.rc, 2) << command << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find("suites/t.toml: --filter nomatch selects none of its 4 cases"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(read_text(dir_ / "reports" / "t" / "index.html"), index);
  EXPECT_EQ(read_text(dir_ / "reports" / "t" / "results.json"), results);
  EXPECT_NE(read_text(dir_ / "junit.xml").find("tests=\"4\""), std::string::npos);
  EXPECT_EQ(goldens(), before);
}

// Damage in the goldens is an ERROR to repair: a truncated golden beside a valid variant, and
// a file where the case's golden folder should be (not NEW with a bless hint).
TEST_F(HarnessCli, DamagedGoldensAreErrorsNotPassesOrNew) {
  ASSERT_EQ(aosuite("bless suites/t.toml").rc, 0);
  const fs::path c = dir_ / "suites" / "goldens" / "t" / "corner-inside-sao-48x27";
  fs::copy_file(c / "with_ao.png", c / "with_ao~ok.png");
  const std::vector<unsigned char> whole = read_file(c / "with_ao.png");
  std::ofstream(c / "with_ao.png", std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(whole.data()),
             static_cast<std::streamsize>(whole.size() / 2));
  test::Outcome r = aosuite("check suites/t.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("ERROR corner-inside-sao-48x27"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("with_ao.png"), std::string::npos) << r.out;

  fs::remove_all(c);
  std::ofstream(c) << "a file where the folder should be";
  r = aosuite("check suites/t.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("ERROR corner-inside-sao-48x27"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cannot read the golden folder"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("to accept corner-inside-sao-48x27"), std::string::npos) << r.out;
}

// `bless --platform` replaces the generic golden on this platform; the variants accepted beside
// it stay accepted.
TEST_F(HarnessCli, PlatformGoldensKeepTheGenericVariants) {
  ASSERT_EQ(aosuite("bless suites/t.toml --filter sao").rc, 0);
  ASSERT_EQ(aosuite("bless suites/t.toml --filter sao --variant darker", broken()).rc, 0);
  ASSERT_EQ(aosuite("bless suites/t.toml --filter sao --platform").rc, 0);
  const test::Outcome r = aosuite("check suites/t.toml --filter sao", broken());
  EXPECT_EQ(r.rc, 0) << r.out << r.err;  // the darker variant still passes
}

// Goldens of a suite without a goldens key land beside the suite file (goldens/<name>), from
// whatever directory it is blessed and checked, or where --goldens says (and the printed bless
// command says so too).
TEST_F(HarnessCli, GoldensFolderIsBesideTheSuiteOrGiven) {
  fs::create_directories(dir_ / "elsewhere" / "deep");
  fs::create_directories(dir_ / "cwd");
  fs::copy_file(dir_ / "suites" / "t.toml", dir_ / "elsewhere" / "deep" / "o.toml");
  EXPECT_EQ(aosuite("bless elsewhere/deep/o.toml --filter inside-sao").rc, 0);
  EXPECT_TRUE(fs::exists(dir_ / "elsewhere" / "deep" / "goldens" / "o" / "corner-inside-sao-48x27" /
                         "with_ao.png"));
  EXPECT_FALSE(fs::exists(dir_ / "goldens"));
  // Checked from another directory, the suite finds them: nothing is NEW.
  const test::Outcome from_elsewhere =
      test::run_shell("cd " + (dir_ / "cwd").string() + " && " + AOSUITE_BIN +
                          " check ../elsewhere/deep/o.toml --filter inside-sao",
                      dir_.path());
  EXPECT_EQ(from_elsewhere.rc, 0) << from_elsewhere.out << from_elsewhere.err;
  EXPECT_EQ(from_elsewhere.out.find("NEW"), std::string::npos) << from_elsewhere.out;
  EXPECT_FALSE(fs::exists(dir_ / "cwd" / "goldens"));
  const test::Outcome r = aosuite("check elsewhere/deep/o.toml --filter inside --goldens g2");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("aosuite bless elsewhere/deep/o.toml --goldens g2 --filter "
                       "'^corner-inside-sao-48x27$'"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "g2"));  // check writes no goldens
}

// bless's log shows each case as it is written, also when redirected to a file.
TEST_F(HarnessCli, BlessLogIsWrittenPerCaseWhenRedirected) {
  std::ofstream(dir_ / "suites" / "t.toml", std::ios::app) << "[[case]]\nscene = \"village\"\n"
                                                              "width = 480\nheight = 270\n";
  const std::string pid_file = (dir_ / "pid").string(), log = (dir_ / "bless.log").string();
  std::system(("cd " + dir_.path().string() + " && (exec " + AOSUITE_BIN +
               " bless suites/t.toml > " + log + " 2>&1 & echo $! > " + pid_file + ")")
                  .c_str());
  // The log's first line must come while bless is still at work: before the last (village)
  // goldens exist. (Buffered output would appear only at exit, after all of them.)
  auto village_goldens = [&] {
    int n = 0;
    for (const auto& [path, bytes] : goldens())
      n += path.string().find("village-") != std::string::npos;
    return n;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (read_text(log).find("BLESSED") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const int written = fs::exists(dir_ / "suites" / "goldens") ? village_goldens() : 0;
  const pid_t pid = std::stoi(read_text(pid_file));
  kill(pid, SIGKILL);
  while (kill(pid, 0) == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_LT(written, 4) << "nothing in the log before bless ended:\n" << read_text(log);
  EXPECT_NE(read_text(log).find(" BLESSED corner-"), std::string::npos) << read_text(log);
}

// Nothing a suite, an option or a shard's results says writes or reads outside its folders.
TEST_F(HarnessCli, PathsStayInsideTheirFolders) {
  test::Outcome r = aosuite("bless suites/t.toml --variant ../../evil");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("--variant '../../evil'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "suites" / "goldens"));
  std::ofstream(dir_ / "suites" / "up.toml") << "name = \"..\"\n[[case]]\nscene = \"corner\"\n";
  r = aosuite("check suites/up.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("suites/up.toml:1:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "index.html"));

  ASSERT_EQ(aosuite("bless suites/t.toml").rc, 0);
  ASSERT_EQ(aosuite("check suites/t.toml --shard 0/2 --report a").rc, 0);
  std::ofstream(dir_ / "secret.txt") << "TOPSECRET";
  const std::string results = read_text(dir_ / "a" / "results.json");
  auto tampered = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = nlohmann::json::parse(results);
    edit(j["cases"][0]);
    std::ofstream(dir_ / "a" / "results.json", std::ios::trunc) << j.dump();
    const test::Outcome m = aosuite("report merge --out m a");
    EXPECT_EQ(m.rc, 2) << m.out << m.err;
    EXPECT_NE(m.err.find("a/results.json: malformed run results"), std::string::npos) << m.err;
    EXPECT_FALSE(fs::exists(dir_ / "m"));
  };
  tampered([](nlohmann::json& c) { c["files"]["with_ao"] = "../../secret.txt"; });
  tampered([&](nlohmann::json& c) { c["files"]["with_ao"] = (dir_ / "secret.txt").string(); });
  tampered([](nlohmann::json& c) { c["id"] = "../../x"; });
  std::ofstream(dir_ / "a" / "results.json", std::ios::trunc) << results;
  // A link in a shard's case folder is not followed into the merged report, nor silently left
  // out of it (the report would point at an image it does not have): refused, by name.
  const std::string id = nlohmann::json::parse(results)["cases"][0]["id"];
  const fs::path image = dir_ / "a" / "cases" / id / "with_ao.png";
  fs::remove(image);
  fs::create_symlink(dir_ / "secret.txt", image);
  r = aosuite("report merge --out m a --partial");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find(id + "/with_ao.png: a link or special file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "m"));
  EXPECT_FALSE(fs::exists(dir_ / "secret.png"));
}

// Paths with bytes that are not UTF-8, or control characters: the report, results.json and
// JUnit stay whole and well-formed.
TEST_F(HarnessCli, OddBytesInPathsAreEscapedEverywhere) {
  const std::string odd = "\"$(printf 'g\\377\\001')\"";
  ASSERT_EQ(aosuite("bless suites/t.toml --goldens " + odd).rc, 0);
  const fs::path g = dir_ / "g\xff\x01" / "corner-inside-sao-48x27" / "with_ao.png";
  ASSERT_TRUE(fs::exists(g));
  std::ofstream(g, std::ios::trunc) << "garbage";
  const test::Outcome r = aosuite("check suites/t.toml --junit junit.xml --goldens " + odd);
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("g\\xff\\x01/corner-inside-sao-48x27/with_ao.png"), std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find('\x01'), std::string::npos);
  const auto results = nlohmann::json::parse(read_text(dir_ / "reports" / "t" / "results.json"));
  EXPECT_EQ(results["cases"].size(), 4u);
  EXPECT_EQ(test::run_shell("xmllint --noout " + (dir_ / "junit.xml").string(), dir_.path()).rc, 0);
  const std::string html = read_text(dir_ / "reports" / "t" / "index.html");
  EXPECT_NE(html.find("g\\\\xff\\\\x01/corner-"), std::string::npos);  // in the page's JSON
  EXPECT_EQ(html.find('\xff'), std::string::npos);
  const test::Outcome missing = aosuite("check \"$(printf 'x\\377.toml')\"");
  EXPECT_EQ(missing.rc, 2);
  EXPECT_NE(missing.err.find("x\\xff.toml"), std::string::npos) << missing.err;
}

// The report's copy of a golden is written whole or not at all, even when the disk is full
// (here: a file size limit).
TEST_F(HarnessCli, ReportGoldenCopiesAreNeverTruncated) {
  ASSERT_EQ(aosuite("bless suites/t.toml").rc, 0);
  cv::Mat noise(400, 400, CV_8UC4);
  cv::randu(noise, cv::Scalar::all(0), cv::Scalar::all(256));
  const fs::path golden =
      dir_ / "suites" / "goldens" / "t" / "corner-inside-sao-48x27" / "with_ao.png";
  write_png_rgba8(golden, noise);
  ASSERT_GT(fs::file_size(golden), 200u * 1024);
  const test::Outcome r =
      test::run_shell("cd " + dir_.path().string() + " && trap '' XFSZ && " + "ulimit -f 200 && " +
                          AOSUITE_BIN + " check suites/t.toml",
                      dir_.path());
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  const fs::path c = dir_ / "reports" / "t" / "cases" / "corner-inside-sao-48x27";
  for (const auto& e : fs::directory_iterator(c)) {
    const std::string name = e.path().filename().string();
    EXPECT_FALSE(name.starts_with(".")) << "temporary left: " << name;
    if (name.ends_with(".png")) {
      EXPECT_NO_THROW(read_png_rgba8(e.path())) << name << " is damaged";
    }
  }
}

// A case whose second golden cannot be written keeps its first; bless says what happened.
// Stale temporaries of a killed bless are cleaned.
TEST_F(HarnessCli, BlessReplacesACaseAllOrNothingAndSaysWhy) {
  std::ofstream(dir_ / "suites" / "t.toml", std::ios::app)
      << "images = [\"with_ao\", \"ao_only\"]\n";
  ASSERT_EQ(aosuite("bless suites/t.toml --filter inside-sao").rc, 0);
  const fs::path c = dir_ / "suites" / "goldens" / "t" / "corner-inside-sao-48x27";
  const std::vector<unsigned char> first = read_file(c / "with_ao.png");
  fs::remove(c / "ao_only.png");
  fs::create_directories(c / "ao_only.png");
  const fs::path stale = c / ".with_ao.png.tmp-AbC123";
  std::ofstream(stale) << "x";
  fs::last_write_time(stale, fs::file_time_type::clock::now() - std::chrono::hours(1));
  const test::Outcome r = aosuite("bless suites/t.toml --filter inside-sao", broken());
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("NOT BLESSED corner-inside-sao-48x27: goldens not written: "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("ao_only.png: is not a file; nothing was replaced"), std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("could not be rendered"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 of 1 cases blessed"), std::string::npos) << r.out;
  EXPECT_EQ(read_file(c / "with_ao.png"), first);
  EXPECT_FALSE(fs::exists(stale));
  for (const auto& e : fs::directory_iterator(c)) {
    EXPECT_FALSE(e.path().filename().string().starts_with(".")) << e.path();
  }
}

// The printed commands are shell-quoted and bless exactly the failing cases; one of them
// blesses them all.
TEST_F(HarnessCli, PrintedBlessCommandsAreQuotedAndExact) {
  fs::create_directories(dir_ / "my 'suites'");
  fs::copy_file(dir_ / "suites" / "t.toml", dir_ / "my 'suites'" / "t.toml");
  const std::string suite = "\"my 'suites'/t.toml\"";
  ASSERT_EQ(aosuite("bless " + suite).rc, 0);
  const auto before = goldens("my 'suites'");
  test::Outcome r = aosuite("check " + suite, broken());
  ASSERT_EQ(r.rc, 1) << r.out << r.err;
  const std::string all =
      "to accept all 2 failing and new cases: " + std::string(AOSUITE_BIN) + " bless ";
  const std::size_t at = r.out.find(all);
  ASSERT_NE(at, std::string::npos) << r.out;
  std::string command = r.out.substr(at + all.size());
  command = command.substr(0, command.find('\n'));
  EXPECT_EQ(command.rfind("'my '\\''suites'\\''/t.toml' --filter '^(corner-", 0), 0u) << command;
  r = test::run_shell(
      "cd " + dir_.path().string() + " && " + broken() + " " + AOSUITE_BIN + " bless " + command,
      dir_.path());
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("2 of 2 cases blessed"), std::string::npos) << r.out;
  for (const auto& [path, bytes] : goldens("my 'suites'")) {
    const bool sao = path.string().find("-sao-") != std::string::npos;
    EXPECT_EQ(before.at(path) == bytes, !sao) << path;
  }
  EXPECT_EQ(aosuite("check " + suite, broken()).rc, 0);
}

}  // namespace
}  // namespace aosuite

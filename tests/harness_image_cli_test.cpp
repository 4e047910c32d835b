// Image cases (images a command writes, or files on disk), folder mode, approving from the
// report, --json and --retries, end to end through the CLI. None of these render a scene, so
// they need no OpenGL.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "compare/opencv.hpp"
#include "exr_fixture.hpp"
#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;

using test::read_text;

// The aosuite under test: this build's, or another build's (AOSUITE_TEST_BIN: the build without
// the AO bench, tests/no_renderer_build.sh, runs these tests against its own).
std::string aosuite_bin() {
  const char* other = std::getenv("AOSUITE_TEST_BIN");
  return other && *other ? other : AOSUITE_BIN;
}

// Whether the aosuite under test has the AO bench beside it.
bool has_ao_bench() {
  return fs::exists(fs::path(aosuite_bin()).parent_path() / "libaosuite_gl.so");
}

cv::Mat flat(int w, int h, cv::Scalar rgba) { return cv::Mat(h, w, CV_8UC4, rgba); }

class ImageCases : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "s");
    // The "renderer": a script that draws the chart in the colour its input file names (a
    // copy of a prepared PNG) and can be told to fail or to dawdle.
    write_png_rgba8(dir_ / "s" / "red.png", flat(8, 6, {255, 0, 0, 255}));
    cv::Mat green = flat(8, 6, {255, 0, 0, 255});
    green.rowRange(0, 3).setTo(cv::Scalar(0, 255, 0, 255));  // half changed: a diff to show
    write_png_rgba8(dir_ / "s" / "green.png", green);
    std::ofstream(dir_ / "s" / "colour.txt") << "red";
    std::ofstream(dir_ / "s" / "draw.sh") << R"SH(#!/bin/sh
set -e
out="$1"; here="$2"
if [ -e "$here/fail" ]; then echo "draw: cannot draw today" >&2; exit 3; fi
cp "$here/$(cat "$here/colour.txt").png" "$out/chart.png"
echo "drew $(cat "$here/colour.txt")" >&2
)SH";
    std::ofstream(dir_ / "s" / "t.toml") << R"(
[defaults]
width = 8
height = 6

[[case]]
name = "chart"
command = ["sh", "{suite_dir}/draw.sh", "{out}", "{suite_dir}"]
outputs = ["chart.png"]
inputs = ["draw.sh", "colour.txt"]
timeout = 20
)";
  }
  test::Outcome aosuite(const std::string& args, const std::string& env = "") {
    return test::run_shell(
        "cd " + dir_.path().string() + " && " + env + " " + aosuite_bin() + " " + args,
        dir_.path());
  }
  std::vector<unsigned char> golden() const {
    return read_file(dir_ / "s" / "goldens" / "t" / "chart" / "chart.png");
  }
  test::TempDir dir_;
};

// The shared objects a run loaded, from the dynamic loader's own record (LD_DEBUG=files lists
// every object it maps into the process, dlopen()ed ones included).
std::string loaded_objects(const std::string& err) {
  std::string out;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);) {
    const std::size_t at = line.find("file=");
    if (at != std::string::npos && line.find("generating link map") != std::string::npos)
      out += line.substr(at + 5, line.find(' ', at) - at - 5) + "\n";
  }
  return out;
}

// The image-regression tool stands on its own: a suite of commands and folder mode map none of
// the AO bench's libraries (GL, EGL, Embree, assimp, OpenCV, libaosuite_gl.so); a suite with a
// scene case does, which shows the record is read right.
TEST_F(ImageCases, AnImageOnlyRunMapsNoRendererLibrary) {
  ASSERT_EQ(aosuite("bless s/t.toml").rc, 0);
  for (const char* d : {"actual", "expected"}) fs::create_directories(dir_ / d);
  fs::copy_file(dir_ / "s" / "red.png", dir_ / "actual" / "x.png");
  fs::copy_file(dir_ / "s" / "green.png", dir_ / "expected" / "x.png");
  const std::string bench_libraries[] = {"libGL",     "libEGL",    "libembree",
                                         "libassimp", "libopencv", "libaosuite_gl.so"};
  for (const char* run : {"check s/t.toml", "check --actual actual --expected expected",
                          "bless --actual actual --expected expected"}) {
    const test::Outcome r = aosuite(run, "LD_DEBUG=files");
    const std::string loaded = loaded_objects(r.err);
    EXPECT_NE(loaded.find("libaosuite_check.so"), std::string::npos) << run << "\n" << loaded;
    for (const std::string& lib : bench_libraries)
      EXPECT_EQ(loaded.find(lib), std::string::npos) << run << " loaded " << lib << "\n" << loaded;
  }
  std::ofstream(dir_ / "s" / "t.toml", std::ios::app)
      << "\n[[case]]\nscene = \"plane\"\nviews = [\"above\"]\ntechniques = [\"sao\"]\n";
  const test::Outcome r = aosuite("check s/t.toml", "LD_DEBUG=files");
  if (!has_ao_bench()) {  // the build without it says so, naming the suite
    EXPECT_EQ(r.rc, 2);
    EXPECT_NE(r.err.find("t.toml:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("built without"), std::string::npos) << r.err;
    return;
  }
  const std::string loaded = loaded_objects(r.err);
  for (const char* lib : {"libaosuite_gl.so", "libembree", "libopencv"})
    EXPECT_NE(loaded.find(lib), std::string::npos) << lib << "\n" << loaded;
}

// Messages say where they looked: a missing suite file by name, a NEW case by the golden it
// looked for (a suite's goldens folder, or folder mode's expected file).
TEST_F(ImageCases, MessagesNameTheFilesTheyAreAbout) {
  test::Outcome r = aosuite("check nope.toml");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("nope.toml: no such suite file"), std::string::npos) << r.err;
  r = aosuite("check s/t.toml");
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.out.find("no golden yet at s/goldens/t/chart/chart.png"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1 case: 0 passed, 0 failed, 1 new"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("-%"), std::string::npos) << r.out;  // nothing measured, nothing shown
  ASSERT_EQ(aosuite("bless s/t.toml").rc, 0);
  std::ofstream(dir_ / "s" / "colour.txt") << "green";
  r = aosuite("check s/t.toml");
  EXPECT_NE(r.out.find("chart 50.00% max Δ 255"), std::string::npos) << r.out;  // how far off
  fs::create_directories(dir_ / "actual");
  fs::create_directories(dir_ / "expected");
  fs::copy_file(dir_ / "s" / "red.png", dir_ / "actual" / "x.png");
  r = aosuite("check --actual actual --expected expected");
  EXPECT_NE(r.out.find("no golden yet at expected/x.png"), std::string::npos) << r.out;
}

// The README's suite template and folder mode's defaults catch a global shading change that
// Resemble's `less` mode alone lets pass at 0.00 %: every pixel 12 levels darker.
TEST_F(ImageCases, TheTemplateAndTheDefaultsCatchAGlobalShadingChange) {
  std::ifstream readme(std::string(AOSUITE_SOURCE_DIR) + "/README.md");
  std::string line, tolerance;
  bool in = false;
  while (std::getline(readme, line)) {
    if (line == "[defaults.tolerance]") in = true;
    if (in && line.empty()) break;
    if (in) tolerance += line + "\n";
  }
  ASSERT_NE(tolerance.find("max_channel_delta"), std::string::npos) << tolerance;
  cv::Mat shade(36, 64, CV_8UC4);
  for (int y = 0; y < shade.rows; ++y)
    for (int x = 0; x < shade.cols; ++x)
      shade.at<cv::Vec4b>(y, x) = cv::Vec4b(uchar(40 + 3 * x), uchar(60 + 2 * y), 120, 255);
  fs::create_directories(dir_ / "actual");
  fs::create_directories(dir_ / "expected");
  write_png_rgba8(dir_ / "expected" / "shade.png", shade);
  cv::Mat darker = shade - cv::Scalar(12, 12, 12, 0);
  write_png_rgba8(dir_ / "actual" / "shade.png", darker);
  // Resemble's `less` mode alone sees nothing: every other limit lifted by name.
  test::Outcome r = aosuite(
      "check --actual actual --expected expected --max-channel-delta 255 "
      "--limit max_mean_shift=255 --limit max_mean_delta=255");
  EXPECT_EQ(r.rc, 0) << r.out;
  // Folder mode's defaults, and the template's tolerance, do.
  r = aosuite("check --actual actual --expected expected");
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_NE(r.out.find("max channel delta 12 (allowed 8)"), std::string::npos) << r.out;
  // The line says what kind of change it was, and results.json records it.
  EXPECT_NE(r.out.find("image changed: darker by 12.0 levels, 64x36 at (0, 0), 2304 px"),
            std::string::npos)
      << r.out;
  const auto results =
      nlohmann::json::parse(read_text(dir_ / "reports" / "folder" / "results.json"));
  EXPECT_EQ(results["cases"][0]["images"][0]["changes"][0]["kind"], "brightness") << results.dump();
  EXPECT_NE(read_text(dir_ / "reports" / "folder" / "index.html").find("darker by 12.0 levels"),
            std::string::npos);  // the page's panel shows it
  std::ofstream(dir_ / "template.toml")
      << tolerance << "[[case]]\nname = \"shade\"\nfiles = [\"actual/shade.png\"]\n";
  fs::create_directories(dir_ / "goldens" / "template" / "shade");
  fs::copy_file(dir_ / "expected" / "shade.png",
                dir_ / "goldens" / "template" / "shade" / "shade.png");
  r = aosuite("check template.toml");
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_NE(r.out.find("max channel delta 12 (allowed 8)"), std::string::npos) << r.out;
}

// The loop a user runs: NEW, approve, PASS (reused), a changed input FAILs with a report, the
// report's image is approved without running the command again, PASS.
TEST_F(ImageCases, ACommandsImagesPassFailAndAreApprovedFromTheReport) {
  test::Outcome r = aosuite("check s/t.toml --junit junit.xml");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("NEW   chart"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "s" / "goldens"));
  EXPECT_NE(r.out.find("or review reports/t/index.html and accept the images it shows: " +
                       aosuite_bin() + " bless s/t.toml --failed --report reports/t"),
            std::string::npos)
      << r.out;
  r = aosuite("bless s/t.toml --failed");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("BLESSED chart"), std::string::npos) << r.out;
  EXPECT_EQ(decode_png_rgba8(golden(), "golden").at<cv::Vec4b>(0, 0), cv::Vec4b(255, 0, 0, 255));

  r = aosuite("check s/t.toml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  r = aosuite("check s/t.toml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("(unchanged, reused)"), std::string::npos) << r.out;
  // A passing case's golden is not rewritten by a plain bless, only with --force.
  r = aosuite("bless s/t.toml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("KEPT chart"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 of 1 cases blessed"), std::string::npos) << r.out;
  EXPECT_NE(aosuite("bless s/t.toml --force").out.find("BLESSED chart"), std::string::npos);

  // A declared input changes: the case is run again (not reused) and fails.
  std::ofstream(dir_ / "s" / "colour.txt", std::ios::trunc) << "green";
  const auto before = golden();
  r = aosuite("check s/t.toml --junit junit.xml");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("FAIL  chart"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("reused"), std::string::npos) << r.out;
  EXPECT_EQ(golden(), before);
  const fs::path c = dir_ / "reports" / "t" / "cases" / "chart";
  EXPECT_TRUE(fs::exists(c / "diff_chart.png"));
  EXPECT_TRUE(fs::exists(c / "golden_chart.png"));
  const auto results = nlohmann::json::parse(read_text(dir_ / "reports" / "t" / "results.json"));
  EXPECT_EQ(results["cases"][0]["kind"], "command");
  EXPECT_EQ(results["cases"][0]["exit_status"], 0);
  EXPECT_NE(results["cases"][0]["command_stderr"].get<std::string>().find("drew green"),
            std::string::npos);
  const std::string junit = read_text(dir_ / "junit.xml");
  EXPECT_NE(junit.find("failures=\"1\""), std::string::npos) << junit;
  // JUnit links the report's panel and the images, and accepts what the report shows.
  const std::string report = fs::canonical(dir_ / "reports" / "t").string();
  EXPECT_NE(junit.find("<system-out>report: " + report + "/index.html#case=chart\n"),
            std::string::npos)
      << junit;
  EXPECT_NE(junit.find("[[ATTACHMENT|" + report + "/cases/chart/diff_chart.png]]"),
            std::string::npos)
      << junit;
  EXPECT_NE(
      junit.find("to accept what the report shows: " + aosuite_bin() +
                 " bless s/t.toml --from-report --report reports/t --filter &#39;^chart$&#39;"),
      std::string::npos)
      << junit;
  EXPECT_NE(read_text(dir_ / "reports" / "t" / "index.html").find("chart"), std::string::npos);

  // Approve from the report: the reviewed image, not a new run (the command now fails).
  std::ofstream(dir_ / "s" / "fail") << "";
  r = aosuite("bless s/t.toml --failed");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(decode_png_rgba8(golden(), "golden").at<cv::Vec4b>(0, 0), cv::Vec4b(0, 255, 0, 255));
  r = aosuite("bless s/t.toml --failed");  // the report has not changed: it is still FAIL...
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  fs::remove(dir_ / "s" / "fail");
  r = aosuite("check s/t.toml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  r = aosuite("bless s/t.toml --failed");  // ...now nothing is left to accept
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("nothing to accept"), std::string::npos) << r.out;

  // Platform goldens for images no GL made: keyed by AOSUITE_PLATFORM, also from a report.
  std::ofstream(dir_ / "s" / "colour.txt", std::ios::trunc) << "red";
  EXPECT_EQ(aosuite("check s/t.toml", "AOSUITE_PLATFORM=ci-box").rc, 1);
  r = aosuite("bless s/t.toml --failed --platform", "AOSUITE_PLATFORM=ci-box");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "s" / "goldens" / "t" / "chart" / "ci-box" / "chart.png"));
  EXPECT_EQ(aosuite("check s/t.toml", "AOSUITE_PLATFORM=ci-box").rc, 0);
  EXPECT_EQ(aosuite("check s/t.toml").rc, 1);  // elsewhere the generic (green) golden holds
  r = aosuite("bless s/t.toml --failed --platform");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;  // no platform known: say so, write nothing
  EXPECT_NE(r.err.find("AOSUITE_PLATFORM"), std::string::npos) << r.err;
}

// A command that fails, hangs or writes nothing is an ERROR (exit 2) with its exit status and
// stderr in the report, never NEW or PASS.
TEST_F(ImageCases, CommandFailuresAreErrorsWithExitStatusAndStderr) {
  std::ofstream(dir_ / "s" / "fail") << "";
  test::Outcome r = aosuite("check s/t.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("ERROR chart"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("command exited with status 3: draw: cannot draw today"), std::string::npos)
      << r.out;
  auto results = nlohmann::json::parse(read_text(dir_ / "reports" / "t" / "results.json"));
  EXPECT_EQ(results["cases"][0]["exit_status"], 3);
  EXPECT_NE(results["cases"][0]["command_stderr"].get<std::string>().find("cannot draw"),
            std::string::npos);
  EXPECT_NE(read_text(dir_ / "reports" / "t" / "index.html").find("cannot draw today"),
            std::string::npos);
  EXPECT_EQ(aosuite("bless s/t.toml").rc, 2);
  EXPECT_FALSE(fs::exists(dir_ / "s" / "goldens" / "t" / "chart" / "chart.png"));
  // A signal is named as one, not read as an exit status (153 = 128 + SIGXFSZ).
  std::ofstream(dir_ / "s" / "sig.toml") << R"(
[[case]]
name = "signalled"
command = ["sh", "-c", "kill -XFSZ $$"]
outputs = ["x.png"]

[[case]]
name = "exited"
command = ["sh", "-c", "exit 153"]
outputs = ["x.png"]
)";
  r = aosuite("check s/sig.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("command was killed by SIGXFSZ (File size limit exceeded)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("command exited with status 153"), std::string::npos) << r.out;
  // The report's ERROR is not something to approve; a missing report or another suite's is a
  // one-line error naming the file.
  r = aosuite("bless s/t.toml --from-report --filter chart");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("NOT BLESSED chart: could not be judged in the report"), std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "s" / "goldens" / "t" / "chart" / "chart.png"));
  for (const char* bad : {"bless s/t.toml --failed --report nowhere",
                          "bless --actual s --expected s --failed --report reports/t"}) {
    r = aosuite(bad);
    EXPECT_EQ(r.rc, 2) << bad << "\n" << r.out << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("results.json"), std::string::npos) << r.err;
  }

  std::ofstream(dir_ / "s" / "t.toml", std::ios::app) << R"(
[[case]]
name = "hangs"
command = ["sleep", "30"]
outputs = ["x.png"]
timeout = 0.5

[[case]]
name = "silent"
command = ["true"]
outputs = ["x.png"]
)";
  const auto t0 = std::chrono::steady_clock::now();
  r = aosuite("check s/t.toml --filter 'hangs|silent' --jobs 2");
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(10));
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("command timed out after 0.5 s and was killed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the command did not write x.png"), std::string::npos) << r.out;
}

// A command never outlives aosuite: what it leaves running (a `setsid` daemon, a double-forked
// orphan) is killed when it exits, when it times out, and when aosuite is stopped by TERM, by
// a terminal's Ctrl-C (SIGINT to aosuite's process group) or by SIGKILL, to aosuite alone or to
// its whole process group (`timeout -s KILL`, `kill -9 -- -PGID`).
TEST_F(ImageCases, NoProcessOfACommandOutlivesIt) {
  std::ofstream(dir_ / "s" / "tree.sh") << R"SH(#!/bin/sh
here="$1"
setsid sh -c 'echo $$ > "$1/daemon.pid"; exec sleep 300' sh "$here" &
( sleep 300 & echo $! > "$here/orphan.pid" )
while [ ! -s "$here/daemon.pid" ]; do sleep 0.01; done
echo $$ > "$here/main.pid"
if [ -e "$here/hang" ]; then sleep 300; fi
cp "$here/red.png" "$2/x.png"
)SH";
  std::ofstream(dir_ / "s" / "tree.toml") << R"(
[[case]]
name = "tree"
command = ["sh", "{suite_dir}/tree.sh", "{suite_dir}", "{out}"]
outputs = ["x.png"]
timeout = 2
)";
  const auto pids = [&] {
    std::vector<pid_t> out;
    for (const char* f : {"main.pid", "daemon.pid", "orphan.pid"})
      out.push_back(static_cast<pid_t>(std::atol(read_text(dir_ / "s" / f).c_str())));
    return out;
  };
  // Gone: no such process (a zombie would still answer kill(pid, 0)).
  const auto all_gone = [&] {
    for (int wait = 0; wait < 100; ++wait) {
      bool alive = false;
      for (pid_t p : pids()) alive = alive || (p > 1 && ::kill(p, 0) == 0);
      if (!alive) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  };
  const auto fresh = [&] {
    for (const char* f : {"main.pid", "daemon.pid", "orphan.pid"}) fs::remove(dir_ / "s" / f);
  };
  test::Outcome r = aosuite("check s/tree.toml --no-reuse");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;  // NEW: the command exited 0 and wrote its image
  EXPECT_NE(pids()[1], 0);
  EXPECT_TRUE(all_gone()) << "exit left processes behind";
  fresh();
  std::ofstream(dir_ / "s" / "hang") << "";
  r = aosuite("check s/tree.toml --no-reuse");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("timed out"), std::string::npos) << r.out;
  EXPECT_TRUE(all_gone()) << "the timeout left processes behind";
  for (const char* how :
       {"kill -TERM $p", "kill -INT -- -$p", "kill -KILL $p", "kill -KILL -- -$p"}) {
    fresh();
    // aosuite in a process group of its own, as a terminal's foreground job is.
    test::run_shell("cd " + dir_.path().string() + " && (setsid " + aosuite_bin() +
                        " check s/tree.toml --no-reuse >/dev/null 2>&1 & p=$!; "
                        "while [ ! -s s/main.pid ]; do sleep 0.02; done; " +
                        how + "; wait $p)",
                    dir_.path());
    EXPECT_NE(pids()[1], 0) << how;
    EXPECT_TRUE(all_gone()) << how << " left processes behind";
  }
}

// One run at a time per report folder and goldens folder: a second one fails at once naming
// the first (pid, command), or waits with --wait; a killed holder's lock is simply taken over.
TEST_F(ImageCases, OneRunAtATimeInAReportOrGoldensFolder) {
  for (const char* s : {"a", "b"}) {
    std::ofstream(dir_ / "s" / (std::string(s) + ".toml"))
        << "[[case]]\nname = \"slow\"\ncommand = [\"sh\", \"-c\", \"touch {suite_dir}/started; "
           "while [ ! -e {suite_dir}/go ]; do sleep 0.02; done; "
           "cp {suite_dir}/red.png {out}/x.png\"]\noutputs = [\"x.png\"]\n";
  }
  // The case's command holds its run until the test says go: no race with a slow machine.
  const auto go = [&] { std::ofstream(dir_ / "s" / "go").put('1'); };
  const auto in_background = [&](const std::string& args) {
    fs::remove(dir_ / "s" / "started");
    fs::remove(dir_ / "s" / "go");
    test::run_shell("cd " + dir_.path().string() + " && (" + aosuite_bin() + " " + args +
                        " >bg.out 2>&1 & echo $! >bg.pid) && while [ ! -e s/started ]; do sleep "
                        "0.01; done",
                    dir_.path());
    return static_cast<pid_t>(std::atol(read_text(dir_ / "bg.pid").c_str()));
  };
  in_background("check s/a.toml --report R");
  test::Outcome r = aosuite("check s/b.toml --report R");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("R: in use by another aosuite (pid "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("check s/a.toml --report R"), std::string::npos) << r.err;
  go();
  r = aosuite("check s/b.toml --report R --wait");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;  // NEW, after the first run let go
  EXPECT_NE(read_text(dir_ / "bg.out").find("NEW   slow"), std::string::npos)
      << read_text(dir_ / "bg.out");
  // Two blesses into one goldens folder, each with its own report folder.
  in_background("bless s/a.toml --goldens G --report R1");
  r = aosuite("bless s/b.toml --goldens G --report R2");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("G: in use by another aosuite"), std::string::npos) << r.err;
  go();
  // Dead once it is gone or a zombie (its files, and so its lock, are released by then).
  const auto await_end = [](pid_t pid) {
    for (int i = 0; i < 1000 && ::kill(pid, 0) == 0; ++i) {
      const std::string stat = read_text(fs::path("/proc") / std::to_string(pid) / "stat");
      if (stat.empty() || stat.find(") Z ") != std::string::npos) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  };
  // The lock belongs to the path: a CI job that deletes and recreates its report folder
  // (`rm -rf D && aosuite check ... --report D`) while another run writes there is refused, and
  // so is a link to the folder.
  const pid_t writer = in_background("check s/a.toml --report D");
  for (const char* folder : {"L", "D"}) {
    test::run_shell("cd " + dir_.path().string() +
                        (folder == std::string("L") ? " && ln -s D L" : " && rm -rf D"),
                    dir_.path());
    r = aosuite(std::string("check s/b.toml --report ") + folder);
    EXPECT_EQ(r.rc, 2) << folder << ": " << r.out << r.err;
    EXPECT_NE(r.err.find("in use by another aosuite (pid " + std::to_string(writer)),
              std::string::npos)
        << folder << ": " << r.err;
  }
  go();
  await_end(writer);
  // One folder named for two jobs of one run is said to be that, not another aosuite.
  r = aosuite("bless s/a.toml --goldens X --report X");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("X: named twice in one run"), std::string::npos) << r.err;
  // A holder killed with SIGKILL leaves no lock behind.
  const pid_t holder = in_background("check s/a.toml --report K");
  ASSERT_EQ(::kill(holder, SIGKILL), 0);
  await_end(holder);
  go();
  r = aosuite("check s/a.toml --report K");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  // A run that stops before writing (nothing selected) leaves no report folder.
  r = aosuite("check s/a.toml --report empty --filter nothing-matches");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "empty"));
}

// Folder mode follows no link and reads no device: a self-looping link, a link to /dev/zero,
// a link out of the folder, a FIFO and a text file are skipped and said, and the run goes on; a
// golden reached through a link is an ERROR, and bless never writes through a linked folder.
TEST_F(ImageCases, FolderModeFollowsNoLinkAndSaysWhatItSkipped) {
  for (const char* d : {"actual/sub", "expected", "outside"}) fs::create_directories(dir_ / d);
  const fs::path red = dir_ / "s" / "red.png";
  fs::copy_file(red, dir_ / "actual" / "a.png");
  fs::copy_file(red, dir_ / "expected" / "a.png");
  fs::copy_file(red, dir_ / "outside" / "red.png");
  fs::create_symlink("loop.png", dir_ / "actual" / "loop.png");
  fs::create_symlink("/dev/zero", dir_ / "actual" / "zero.png");
  fs::create_symlink("../outside/red.png", dir_ / "actual" / "out.png");
  ASSERT_EQ(::mkfifo((dir_ / "actual" / "fifo.png").c_str(), 0644), 0);
  std::ofstream(dir_ / "actual" / "notes.txt") << "not an image";
  test::Outcome r = aosuite("check --actual actual --expected expected");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("1 image: 1 unchanged"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("skipped 5 files: "), std::string::npos) << r.out;
  for (const char* said :
       {"actual/loop.png (a symbolic link (not followed))", "actual/zero.png (a symbolic link",
        "actual/out.png (a symbolic link", "actual/fifo.png (not a regular file)",
        "actual/notes.txt (not an image file)"}) {
    EXPECT_NE(r.out.find(said), std::string::npos) << said << "\n" << r.out;
  }
  // An actual image that is a link is not a deleted one: its expected image stays, and says so.
  fs::copy_file(red, dir_ / "expected" / "out.png");
  r = aosuite("check --actual actual --expected expected");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find(" 0 deleted"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("expected/out.png (its actual file was skipped; left as it is)"),
            std::string::npos)
      << r.out;
  aosuite("bless --actual actual --expected expected");
  EXPECT_TRUE(fs::exists(dir_ / "expected" / "out.png"));
  fs::remove(dir_ / "expected" / "out.png");
  // A golden that is a link, and one under a linked folder: ERROR, and bless writes nothing.
  fs::copy_file(red, dir_ / "actual" / "b.png");
  fs::create_symlink("../outside/red.png", dir_ / "expected" / "b.png");
  fs::copy_file(red, dir_ / "actual" / "sub" / "c.png");
  fs::create_symlink("../outside", dir_ / "expected" / "sub");
  r = aosuite("check --actual actual --expected expected");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("expected/sub: a symbolic link; nothing is written through it"),
            std::string::npos)
      << r.out;
  r = aosuite("bless --actual actual --expected expected");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "outside" / "c.png"));
  EXPECT_TRUE(fs::is_symlink(dir_ / "expected" / "b.png"));
  // Nothing but skipped files: said, exit 2, not "0 cases".
  fs::create_directories(dir_ / "only");
  fs::create_symlink("/dev/zero", dir_ / "only" / "z.png");
  r = aosuite("check --actual only --expected only");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("no image file under only or only; skipped 2: only/z.png"),
            std::string::npos)
      << r.err;
}

// Every read is bounded by the memory budget and names the file it refuses: a shard's 2 GiB
// results.json, a command's 2 GiB output (sparse files: nothing is written to disk).
TEST_F(ImageCases, OversizedFilesAreRefusedByName) {
  fs::create_directories(dir_ / "a");
  std::ofstream(dir_ / "a" / "results.json").close();
  fs::resize_file(dir_ / "a" / "results.json", std::uintmax_t{2} << 30);
  test::Outcome r = aosuite("report merge --out m a");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("a/results.json: file larger than the 1024 MiB memory budget"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "m"));
  std::ofstream(dir_ / "s" / "big.toml") << R"(
[[case]]
name = "big"
command = ["truncate", "-s", "2G", "{out}/x.png"]
outputs = ["x.png"]
)";
  r = aosuite("check s/big.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("x.png: file larger than the 1024 MiB memory budget"), std::string::npos)
      << r.out;
}

// A suite's files are regular files: a `files` entry, an input or a golden that is (or links
// to) a device such as /dev/zero, or a FIFO, is an error naming it at once, never read whole.
TEST_F(ImageCases, DevicesAndFifosInASuiteAreRefusedByName) {
  fs::create_symlink("/dev/zero", dir_ / "s" / "zero.png");
  ASSERT_EQ(::mkfifo((dir_ / "s" / "fifo.png").c_str(), 0600), 0);
  for (const char* entry : {"zero.png", "fifo.png"}) {
    std::ofstream(dir_ / "s" / "f.toml")
        << "[[case]]\nname = \"f\"\nfiles = [\"" << entry << "\"]\n";
    const auto t0 = std::chrono::steady_clock::now();
    const test::Outcome r = aosuite("check s/f.toml");
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(20)) << entry;
    EXPECT_EQ(r.rc, 2) << entry << ": " << r.out << r.err;
    EXPECT_NE((r.out + r.err).find(std::string(entry) + ": is a "), std::string::npos)
        << entry << ": " << r.out << r.err;
  }
  std::ofstream(dir_ / "s" / "i.toml") << R"(
[[case]]
name = "i"
command = ["cp", "{suite_dir}/red.png", "{out}/x.png"]
inputs = ["zero.png"]
outputs = ["x.png"]
)";
  test::Outcome r = aosuite("check s/i.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("zero.png is not a regular file"), std::string::npos) << r.err;
  // A golden that links to /dev/zero leaves the goldens folder; followed, it is a device.
  ASSERT_EQ(aosuite("bless s/t.toml").rc, 0);
  const fs::path golden = dir_ / "s" / "goldens" / "t" / "chart" / "chart.png";
  fs::remove(golden);
  fs::create_symlink("/dev/zero", golden);
  r = aosuite("check s/t.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("chart.png: is a link out of s/goldens/t (to /dev/zero)"), std::string::npos)
      << r.out;
  const std::string suite = read_text(dir_ / "s" / "t.toml");
  std::ofstream(dir_ / "s" / "t.toml") << "follow_links = true\n" << suite;
  r = aosuite("check s/t.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("chart.png: is a device, not a regular file"), std::string::npos) << r.out;
}

// Under CI (or --report-images failures) the report keeps the images of the cases a reviewer
// must look at; a passing case keeps its numbers and names its golden, and no image: the
// artifact CI uploads is what needs review. --report-images all, or --diff-all, keep them all.
TEST_F(ImageCases, UnderCiOnlyCasesToReviewKeepTheirImages) {
  for (const char* d : {"actual", "expected"}) fs::create_directories(dir_ / d);
  const cv::Mat red = flat(8, 6, {255, 0, 0, 255});
  cv::Mat near = red.clone(), changed = red.clone();
  near.at<cv::Vec4b>(2, 3) = {250, 0, 0, 255};  // within the default channel delta: passes
  changed.rowRange(0, 3).setTo(cv::Scalar(0, 255, 0, 255));
  for (const char* name : {"same.png", "near.png", "changed.png"})
    write_png_rgba8(dir_ / "expected" / name, red);
  write_png_rgba8(dir_ / "actual" / "same.png", red);
  write_png_rgba8(dir_ / "actual" / "near.png", near);
  write_png_rgba8(dir_ / "actual" / "changed.png", changed);
  const std::string check = "check --actual actual --expected expected --report rep";
  for (int run = 0; run < 2; ++run) {  // the second: nothing left to reuse, the same verdicts
    const test::Outcome r = aosuite(check, "CI=true");
    ASSERT_EQ(r.rc, 1) << r.out << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "rep" / "cases" / "same.png"));
    EXPECT_FALSE(fs::exists(dir_ / "rep" / "cases" / "near.png"));
    EXPECT_TRUE(fs::exists(dir_ / "rep" / "cases" / "changed.png" / "image.png"));
    EXPECT_TRUE(fs::exists(dir_ / "rep" / "cases" / "changed.png" / "golden_image.png"));
    const auto results = nlohmann::json::parse(read_text(dir_ / "rep" / "results.json"));
    for (const nlohmann::json& c : results.at("cases")) {
      const bool passed = c.at("status") == "PASS";
      EXPECT_EQ(c.at("images_left_out"), passed) << c.at("id");
      EXPECT_EQ(c.at("files").empty(), passed) << c.at("id");
      EXPECT_EQ(c.at("images").at(0).at("golden"), "expected/" + c.at("id").get<std::string>());
      if (c.at("id") == "near.png") {
        EXPECT_EQ(c.at("images").at(0).at("max_channel_delta"), 5);
      }
    }
  }
  EXPECT_EQ(aosuite(check + " --report-images all", "CI=true").rc, 1);
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "cases" / "near.png" / "golden_image.png"));
  EXPECT_EQ(aosuite(check, "env -u CI").rc, 1);
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "cases" / "same.png" / "image.png"));
  fs::remove_all(dir_ / "rep");
  EXPECT_EQ(aosuite(check + " --diff-all", "CI=true").rc, 1);
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "cases" / "near.png" / "golden_image.png"));
  const test::Outcome both = aosuite(check + " --diff-all --report-images failures");
  EXPECT_EQ(both.rc, 2) << both.out << both.err;
  EXPECT_NE(both.err.find("--diff-all writes passing cases' diffs"), std::string::npos) << both.err;
}

// One render written as frame.png and frame.exr is one case of two images, named apart by their
// types, each judged by the tolerance for its kind: the PNG by Resemble's limits, the EXR by
// [tolerance.float]'s gates.
TEST_F(ImageCases, ACommandMayWriteSeveralFileTypes) {
  test::write_exr(dir_ / "s" / "ao.exr", 8, 6, {"Y"}, std::vector<float>(48, 0.5f));
  std::ofstream(dir_ / "s" / "draw2.sh") << R"SH(#!/bin/sh
cp "$2/red.png" "$1/frame.png" && cp "$2/ao.exr" "$1/frame.exr"
)SH";
  std::ofstream(dir_ / "s" / "t.toml") << R"(
[[case]]
name = "frame"
command = ["sh", "{suite_dir}/draw2.sh", "{out}", "{suite_dir}"]
outputs = ["frame.png", "frame.exr"]
inputs = ["draw2.sh", "red.png", "ao.exr"]
[case.tolerance]
max_channel_delta = 8
float = { rmse = { max = 0.01 } }
)";
  test::Outcome r = aosuite("check s/t.toml");
  ASSERT_EQ(r.rc, 1) << r.out << r.err;
  ASSERT_EQ(aosuite("bless s/t.toml").rc, 0);
  const fs::path goldens = dir_ / "s" / "goldens" / "t" / "frame";
  EXPECT_TRUE(fs::exists(goldens / "frame_png.png"));
  EXPECT_TRUE(fs::exists(goldens / "frame_exr.exr"));
  EXPECT_EQ(aosuite("check s/t.toml").rc, 0);
  // The EXR moves within its float gate, the PNG within its channel delta: a pass.
  test::write_exr(dir_ / "s" / "ao.exr", 8, 6, {"Y"}, std::vector<float>(48, 0.505f));
  cv::Mat near = flat(8, 6, {255, 0, 0, 255});
  near.at<cv::Vec4b>(1, 1) = {251, 0, 0, 255};
  write_png_rgba8(dir_ / "s" / "red.png", near);
  r = aosuite("check s/t.toml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  // Beyond it: a failure that names the EXR's gate, not the PNG.
  test::write_exr(dir_ / "s" / "ao.exr", 8, 6, {"Y"}, std::vector<float>(48, 0.6f));
  r = aosuite("check s/t.toml");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  const auto results = nlohmann::json::parse(read_text(dir_ / "reports" / "t" / "results.json"));
  const nlohmann::json& images = results.at("cases").at(0).at("images");
  ASSERT_EQ(images.size(), 2u);
  EXPECT_EQ(images.at(0).at("image"), "frame_png");
  EXPECT_EQ(images.at(0).at("status"), "PASS");
  EXPECT_EQ(images.at(1).at("image"), "frame_exr");
  EXPECT_EQ(images.at(1).at("status"), "FAIL");
  EXPECT_EQ(images.at(1).at("gates").at(0).at("metric"), "rmse") << images.at(1);
}

// Every command's help names each option's value by what it is ("--scene SCENE=village"), never
// by its C++ type ("TEXT", "INT", "FLOAT").
TEST_F(ImageCases, EveryOptionNamesItsValue) {
  std::vector<std::string> commands = {"compare", "check", "bless", "report merge",
                                       "tolerances suggest"};
  if (has_ao_bench()) {
    for (const char* c :
         {"render", "scenes", "viewpoints", "pmi-study", "error", "sweep", "tune", "gl-info"})
      commands.push_back(c);
  }
  for (const std::string& c : commands) {
    const test::Outcome r = aosuite(c + " --help");
    EXPECT_EQ(r.rc, 0) << c << r.err;
    for (const char* type : {" TEXT", " INT", " UINT", " FLOAT", " NUMBER"}) {
      for (std::size_t at = r.out.find(type); at != std::string::npos;
           at = r.out.find(type, at + 1)) {
        const char next =
            at + std::strlen(type) < r.out.size() ? r.out[at + std::strlen(type)] : ' ';
        EXPECT_FALSE(next == ' ' || next == '=' || next == '\n' || next == ':')
            << c << ":" << type << "\n"
            << r.out;
      }
    }
  }
}

// A reader that goes away (`| head -1`) does not stop a bless half way: every case is
// blessed and the exit status is bless's own, not SIGPIPE's.
TEST_F(ImageCases, BlessIntoAClosedPipeBlessesEveryCase) {
  std::ofstream suite(dir_ / "s" / "many.toml");
  for (int i = 0; i < 12; ++i) {
    suite << "[[case]]\nname = \"c" << i << "\"\ncommand = [\"sh\", \"-c\", \"sleep 0.05; cp "
          << "{suite_dir}/red.png {out}/x.png\"]\noutputs = [\"x.png\"]\ninputs = []\n";
  }
  suite.close();
  const test::Outcome r =
      test::run_shell("cd " + dir_.path().string() + " && { " + aosuite_bin() +
                          " bless s/many.toml --jobs 1; echo $? > rc.txt; } | head -1",
                      dir_.path());
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  EXPECT_EQ(read_text(dir_ / "rc.txt"), "0\n") << r.err;
  for (int i = 0; i < 12; ++i) {
    EXPECT_TRUE(fs::exists(dir_ / "s" / "goldens" / "many" / fmt::format("c{}", i) / "x.png")) << i;
  }
}

// A page that cannot be written (a full disk; here a file size limit) leaves no page, never
// the last run's: its PASS beside this run's FAIL in results.json and this run's images.
TEST_F(ImageCases, AFailedPageWriteLeavesNoOlderPage) {
  ASSERT_EQ(aosuite("bless s/t.toml").rc, 0);
  ASSERT_EQ(aosuite("check s/t.toml").rc, 0);
  const fs::path page = dir_ / "reports" / "t" / "index.html";
  ASSERT_TRUE(fs::exists(page));
  ASSERT_GT(fs::file_size(page), 16u << 10);  // over the limit below, unlike results.json
  std::ofstream(dir_ / "s" / "colour.txt") << "green";
  const test::Outcome r = aosuite("check s/t.toml", "trap '' XFSZ; ulimit -f 16;");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("index.html"), std::string::npos) << r.err;
  const auto results = nlohmann::json::parse(read_text(dir_ / "reports" / "t" / "results.json"));
  EXPECT_EQ(results["cases"][0]["status"], "FAIL");
  EXPECT_FALSE(fs::exists(page)) << read_text(page).substr(0, 200);
}

// A link may not lead out of the suite's folder (a `files` entry, or a folder on its way), out
// of a command's {out} (a file or folder it links), or out of the goldens folder: each is an
// ERROR naming it, and bless writes nothing from it. A link within its folder is followed, and
// `follow_links = true` follows them all.
TEST_F(ImageCases, LinksOutOfASuitesFoldersAreErrorsUnlessAllowed) {
  fs::create_directories(dir_ / "outside" / "d");
  fs::copy_file(dir_ / "s" / "green.png", dir_ / "outside" / "secret.png");
  fs::copy_file(dir_ / "s" / "green.png", dir_ / "outside" / "d" / "a.png");
  fs::create_symlink(dir_ / "outside" / "secret.png", dir_ / "s" / "lnk.png");
  fs::create_symlink(dir_ / "outside" / "d", dir_ / "s" / "ldir");
  fs::create_symlink("red.png", dir_ / "s" / "inner.png");
  const std::string outside = (dir_ / "outside").string();
  std::ofstream(dir_ / "s" / "l.toml") << R"(
[[case]]
name = "file"
files = ["lnk.png"]

[[case]]
name = "folder"
files = ["ldir/a.png"]

[[case]]
name = "out_file"
command = ["ln", "-s", ")" + outside + R"(/secret.png", "{out}/a.png"]
outputs = ["a.png"]

[[case]]
name = "out_folder"
command = ["ln", "-s", ")" + outside + R"(/d", "{out}/sub"]
outputs = ["sub/a.png"]

[[case]]
name = "inner"
files = ["inner.png"]
)";
  test::Outcome r = aosuite("bless s/l.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  for (const char* id : {"file", "folder", "out_file", "out_folder"}) {
    EXPECT_NE(r.out.find(std::string("NOT BLESSED ") + id), std::string::npos)
        << id << ": " << r.out;
    EXPECT_FALSE(fs::exists(dir_ / "s" / "goldens" / "l" / id)) << id;
  }
  EXPECT_NE(r.out.find("lnk.png: is a link out of"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("a.png: is a link out of"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("`follow_links = true` in the suite allows it"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "s" / "goldens" / "l" / "inner" / "inner.png"));
  // A goldens folder of a case that is a link out of the goldens folder.
  ASSERT_EQ(aosuite("bless s/t.toml").rc, 0);
  fs::rename(dir_ / "s" / "goldens" / "t" / "chart", dir_ / "outside" / "chart");
  fs::create_symlink(dir_ / "outside" / "chart", dir_ / "s" / "goldens" / "t" / "chart");
  r = aosuite("check s/t.toml");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("chart.png: is a link out of s/goldens/t"), std::string::npos) << r.out;
  // Allowed: the same suite passes, and bless takes the linked files.
  for (const char* suite : {"l", "t"}) {
    const std::string text = read_text(dir_ / "s" / (std::string(suite) + ".toml"));
    std::ofstream(dir_ / "s" / (std::string(suite) + ".toml")) << "follow_links = true\n" << text;
  }
  EXPECT_EQ(aosuite("check s/t.toml").rc, 0);
  r = aosuite("bless s/l.toml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(read_file(dir_ / "s" / "goldens" / "l" / "file" / "lnk.png"),
            read_file(dir_ / "outside" / "secret.png"));
}

// Reuse is safe by default (issue 40): a command case is run again when what it runs changes,
// whether or not the suite lists it: an edited script named by an argument, a rebuilt program
// found on PATH, a declared environment variable; a case that declares nothing it reads is
// never reused, and says so. Each change here draws another image, so each re-run fails.
TEST_F(ImageCases, AChangedScriptProgramOrDeclaredVariableIsRunAgainAndFails) {
  fs::create_directories(dir_ / "bin");
  const auto write_script = [&](const fs::path& file, const std::string& colour) {
    std::ofstream(file, std::ios::trunc)
        << "#!/bin/sh\ncp \"" << (dir_ / "s").string() << "/" << colour << ".png\" \"$1/a.png\"\n";
    fs::permissions(file, fs::perms::owner_all);
  };
  write_script(dir_ / "s" / "paint.sh", "red");
  write_script(dir_ / "bin" / "paint", "red");
  std::ofstream(dir_ / "s" / "r.toml") << R"(
[[case]]
name = "script"
command = ["sh", "{suite_dir}/paint.sh", "{out}"]
outputs = ["a.png"]
inputs = []

[[case]]
name = "program"
command = ["paint", "{out}"]
outputs = ["a.png"]
inputs = []

[[case]]
name = "variable"
command = ["sh", "-c", "cp {suite_dir}/$COLOUR.png {out}/a.png"]
outputs = ["a.png"]
env = ["COLOUR"]

[[case]]
name = "undeclared"
command = ["sh", "{suite_dir}/paint.sh", "{out}"]
outputs = ["a.png"]
)";
  const std::string env = "PATH=" + (dir_ / "bin").string() + ":$PATH COLOUR=red";
  ASSERT_EQ(aosuite("bless s/r.toml", env).rc, 0);
  ASSERT_EQ(aosuite("check s/r.toml", env).rc, 0);
  test::Outcome r = aosuite("check s/r.toml", env);  // nothing changed: reused where it may be
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  const auto reused = [](const std::string& out) {
    std::size_t n = 0;
    for (std::size_t at = 0; (at = out.find("(unchanged, reused)", at)) != std::string::npos; ++at)
      ++n;
    return n;
  };
  EXPECT_EQ(reused(r.out), 3u) << r.out;
  EXPECT_NE(r.out.find("(run again: the case declares no inputs or env"), std::string::npos)
      << r.out;
  const auto results = nlohmann::json::parse(read_text(dir_ / "reports" / "r" / "results.json"));
  for (const auto& c : results.at("cases")) {
    EXPECT_EQ(c.at("not_reused").get<std::string>().empty(), c.at("id") != "undeclared") << c;
  }

  write_script(dir_ / "s" / "paint.sh", "green");  // the script edited
  write_script(dir_ / "bin" / "paint", "green");   // the program rebuilt
  r = aosuite("check s/r.toml", "PATH=" + (dir_ / "bin").string() + ":$PATH COLOUR=green");
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_EQ(reused(r.out), 0u) << r.out;
  for (const char* id : {"script", "program", "variable", "undeclared"})
    EXPECT_NE(r.out.find(std::string("FAIL  ") + id), std::string::npos) << id << "\n" << r.out;
}

// An ERROR is never reused: its cause may lie outside every hash (here the EXR library beside
// the binary, missing, then installed), so the next run judges the case again.
TEST_F(ImageCases, AnErrorIsJudgedAgainOnceItsCauseIsGone) {
  const fs::path build = fs::path(aosuite_bin()).parent_path(), bin = dir_ / "bin";
  fs::create_directories(bin);
  for (const char* f : {"aosuite", "libaosuite_check.so"}) fs::copy_file(build / f, bin / f);
  for (const char* d : {"actual", "expected"}) fs::create_directories(dir_ / d);
  const fs::path exr = fs::path(AOSUITE_SOURCE_DIR) / "fuzz" / "corpus" / "exr";
  fs::copy_file(exr / "rgb_small.exr", dir_ / "actual" / "x.exr");
  fs::copy_file(exr / "grey_8x6.exr", dir_ / "expected" / "x.exr");
  const std::string check = "cd " + dir_.path().string() +
                            " && bin/aosuite check --actual actual --expected expected " +
                            "--gate rmse.max=1";
  test::Outcome r = test::run_shell(check, dir_.path());
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("libaosuite_exr.so"), std::string::npos) << r.out;
  fs::copy_file(build / "libaosuite_exr.so", bin / "libaosuite_exr.so");
  r = test::run_shell(check, dir_.path());
  EXPECT_EQ(r.rc, 1) << r.out << r.err;  // judged: an RGB image against a grey one
  EXPECT_EQ(r.out.find("reused"), std::string::npos) << r.out;
}

// `bless --failed --report R` with no suite takes the suite that R's results.json names, only if
// that suite file is the suite the report was made from: results.json is data, not authority.
TEST_F(ImageCases, BlessFromAReportChecksTheSuiteItNames) {
  std::ofstream(dir_ / "s" / "other.toml") << "[[case]]\nname = \"o\"\nfiles = [\"red.png\"]\n";
  ASSERT_EQ(aosuite("check s/t.toml").rc, 1);  // NEW
  const fs::path results = dir_ / "reports" / "t" / "results.json";
  const std::string honest = read_text(results);
  nlohmann::json j = nlohmann::json::parse(honest);
  j["suite_file"] = "s/other.toml";
  std::ofstream(results, std::ios::trunc) << j.dump();
  test::Outcome r = aosuite("bless --failed --report reports/t");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("whose suite is 'other', not 't'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "s" / "goldens" / "other"));
  std::ofstream(results, std::ios::trunc) << honest;
  r = aosuite("bless --failed --report reports/t");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("/s/t.toml (from reports/t/results.json)"), std::string::npos) << r.out;
  EXPECT_EQ(golden(), read_file(dir_ / "reports" / "t" / "cases" / "chart" / "chart.png"));
}

// results.json names the suite file, or folder mode's two folders, by absolute path: `bless
// --failed --report DIR` works from any directory, not only the one check ran in.
TEST_F(ImageCases, BlessFromAReportWorksFromAnyDirectory) {
  fs::create_directories(dir_ / "elsewhere");
  const auto from_elsewhere = [&](const std::string& args) {
    return test::run_shell(
        "cd " + (dir_ / "elsewhere").string() + " && " + aosuite_bin() + " " + args, dir_.path());
  };
  ASSERT_EQ(aosuite("check s/t.toml").rc, 1);  // NEW
  test::Outcome r = from_elsewhere("bless --failed --report ../reports/t");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(golden(), read_file(dir_ / "reports" / "t" / "cases" / "chart" / "chart.png"));

  fs::create_directories(dir_ / "act");
  fs::create_directories(dir_ / "exp");
  fs::copy_file(dir_ / "s" / "red.png", dir_ / "act" / "x.png");
  fs::copy_file(dir_ / "s" / "green.png", dir_ / "exp" / "x.png");
  ASSERT_EQ(aosuite("check --actual act --expected exp --report reports/f").rc, 1);
  r = from_elsewhere("bless --failed --report ../reports/f");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(read_file(dir_ / "exp" / "x.png"), read_file(dir_ / "s" / "red.png"));
  EXPECT_FALSE(fs::exists(dir_ / "elsewhere" / "exp"));
}

// Two-sided budgets (Mozilla reftest's fuzzy ranges): a case known to differ says how much,
// `channel_delta = [min, max]` and `differing_pixels = [min, max]` (or a bare maximum), and
// fails when the difference outgrows the budget or disappears (then the budget is stale).
TEST_F(ImageCases, TwoSidedBudgetsFailAboveAndBelow) {
  const auto draw = [&](int pixels, int delta) {
    cv::Mat m = flat(8, 6, {100, 100, 100, 255});
    for (int i = 0; i < pixels; ++i) m.at<cv::Vec4b>(i / 8, i % 8)[0] = std::uint8_t(100 + delta);
    write_png_rgba8(dir_ / "s" / "x.png", m);
  };
  const auto suite = [&](const std::string& tolerance) {
    std::ofstream(dir_ / "s" / "b.toml", std::ios::trunc)
        << "[[case]]\nname = \"x\"\nfiles = [\"x.png\"]\n[case.tolerance]\n"
        << tolerance;
  };
  const auto check = [&](const std::string& tolerance, int pixels, int delta) {
    suite(tolerance);
    draw(pixels, delta);
    return aosuite("check s/b.toml");
  };
  suite("");
  draw(0, 0);
  ASSERT_EQ(aosuite("bless s/b.toml").rc, 0);
  // The budgets under test alone: every other limit lifted by name.
  const std::string means = "max_mean_shift = 255\nmax_mean_delta = 255\n";
  const std::string lifted = means + "max_channel_delta = 255\n";
  const std::string delta = "channel_delta = [2, 8]\nmax_mismatch_percent = 100\n" + means;
  EXPECT_EQ(check(delta, 5, 5).rc, 0);
  test::Outcome r = check(delta, 5, 12);
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.out.find("max channel delta 12 (allowed 8)"), std::string::npos) << r.out;
  r = check(delta, 0, 0);  // byte-identical: the known difference is gone
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.out.find("max channel delta 0 (budget 2..8: the difference it allows for is gone"),
            std::string::npos)
      << r.out;
  const std::string pixels = "differing_pixels = [1, 10]\nmax_mismatch_percent = 100\n" + lifted;
  EXPECT_EQ(check(pixels, 5, 30).rc, 0);
  r = check(pixels, 20, 30);
  EXPECT_EQ(r.rc, 1);
  EXPECT_NE(r.out.find("20 differing pixels (budget 1..10)"), std::string::npos) << r.out;
  EXPECT_EQ(check(pixels, 0, 0).rc, 1);
  EXPECT_EQ(check("differing_pixels = 3\nmax_mismatch_percent = 100\n" + lifted, 3, 30).rc, 0);
  EXPECT_EQ(check("differing_pixels = 3\nmax_mismatch_percent = 100\n" + lifted, 4, 30).rc, 1);
  r = check("differing_pixels = [5, 2]\n", 0, 0);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("differing_pixels: min 5 is above max 2"), std::string::npos) << r.err;
  r = check("channel_delta = [1, 4]\nmax_channel_delta = 4\n", 0, 0);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("not both"), std::string::npos) << r.err;
}

// A budget that a passing image uses under a tenth of is named as stale, on one line and in
// results.json, so tolerances tighten over time; a budget in use is not, nor is one whose
// image is byte-identical (nothing was measured).
TEST_F(ImageCases, BudgetsAPassUsesUnderATenthOfAreStale) {
  cv::Mat base = flat(8, 6, {100, 100, 100, 255});
  write_png_rgba8(dir_ / "s" / "x.png", base);
  const auto check = [&](const std::string& tolerance) {
    std::ofstream(dir_ / "s" / "b.toml", std::ios::trunc)
        << "[[case]]\nname = \"x\"\nfiles = [\"x.png\"]\n[case.tolerance]\n"
        << tolerance;
    return aosuite("check s/b.toml");
  };
  ASSERT_EQ(check("").rc, 1);  // NEW
  ASSERT_EQ(aosuite("bless s/b.toml").rc, 0);
  EXPECT_EQ(check("max_mismatch_percent = 50\n").out.find("stale"), std::string::npos);
  base.at<cv::Vec4b>(0, 0)[0] = 200;  // 1 of 48 pixels: 2.08 %
  write_png_rgba8(dir_ / "s" / "x.png", base);
  // The mismatch budget and the gate alone: the channel limits lifted by name.
  const std::string lifted =
      "max_channel_delta = 255\nmax_mean_shift = 255\nmax_mean_delta = 255\n";
  test::Outcome r = check("max_mismatch_percent = 50\nrmse = { max = 1 }\n" + lifted);
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("stale budgets: 1 passing image use under a tenth of a limit (x x: "
                       "max_mismatch_percent 50 (used 2.08)"),
            std::string::npos)
      << r.out;
  const auto stale = nlohmann::json::parse(read_text(dir_ / "reports" / "b" / "results.json"))
                         .at("cases")
                         .at(0)
                         .at("images")
                         .at(0)
                         .at("stale");
  ASSERT_EQ(stale.size(), 2u) << stale;
  EXPECT_TRUE(stale[1].get<std::string>().starts_with("rmse.max_value 1 (used ")) << stale;
  r = check("max_mismatch_percent = 10\n" + lifted);  // 2.08 is over a tenth of 10: in use
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_EQ(r.out.find("stale"), std::string::npos) << r.out;
}

// A noisy command's output is kept as its last 64 KiB, after a line giving its full size.
TEST_F(ImageCases, ACommandsOutputIsKeptAsItsLast64KiB) {
  std::ofstream(dir_ / "s" / "noisy.toml") << R"(
[[case]]
name = "noisy"
command = ["sh", "-c", "seq 1 100000 >&2; seq 1 100000; cp {suite_dir}/red.png {out}/x.png"]
outputs = ["x.png"]
)";
  ASSERT_EQ(aosuite("check s/noisy.toml").rc, 1);
  for (const char* f : {"stderr.txt", "stdout.txt"}) {
    const std::string kept = read_text(dir_ / "reports" / "noisy" / "cases" / "noisy" / f);
    EXPECT_LT(kept.size(), 65 * 1024u) << f;
    EXPECT_TRUE(kept.starts_with("[aosuite: 588895 bytes written; the last 65536 kept]\n")) << f;
    EXPECT_TRUE(kept.ends_with("\n99999\n100000\n")) << f;
  }
}

// A command runs in a folder of its own run's ({out}, its working folder): two runs of one case
// never share it, so one never judges what the other wrote, and none is left afterwards.
TEST_F(ImageCases, EachRunsCommandWritesInAFolderOfItsOwnLeftNowhere) {
  std::ofstream(dir_ / "s" / "o.toml") << R"(
[[case]]
name = "c"
command = ["sh", "-c", "pwd >> {suite_dir}/cwd.txt; echo {out} >> {suite_dir}/out.txt; cp {suite_dir}/red.png {out}/x.png"]
outputs = ["x.png"]
)";
  for (int run = 0; run < 2; ++run) {
    const test::Outcome r = aosuite("check s/o.toml --no-reuse");
    EXPECT_EQ(r.rc, 1) << r.out << r.err;  // NEW
  }
  EXPECT_EQ(read_text(dir_ / "s" / "cwd.txt"), read_text(dir_ / "s" / "out.txt"));
  std::istringstream lines(read_text(dir_ / "s" / "out.txt"));
  std::vector<std::string> outs;
  for (std::string line; std::getline(lines, line);) outs.push_back(line);
  ASSERT_EQ(outs.size(), 2u);
  EXPECT_NE(outs[0], outs[1]);
  const std::string case_dir = fs::canonical(dir_ / "reports" / "o" / "cases" / "c").string();
  for (const std::string& out : outs) {
    EXPECT_TRUE(out.starts_with(case_dir + "/.out-")) << out;
    EXPECT_FALSE(fs::exists(out)) << out;
  }
}

// A command that floods stdout holds little disk while it runs: all but the kept tail is freed
// as it writes, not once it ends.
TEST_F(ImageCases, ACommandsFloodOfOutputIsFreedWhileItRuns) {
  std::ofstream(dir_ / "s" / "flood.toml") << R"(
[[case]]
name = "flood"
command = ["sh", "-c", "head -c 300000000 /dev/zero; touch {suite_dir}/wrote; while [ ! -e {suite_dir}/seen ]; do sleep 0.02; done; cp {suite_dir}/red.png {out}/x.png"]
outputs = ["x.png"]
timeout = 30
)";
  test::run_shell("cd " + dir_.path().string() + " && (" + aosuite_bin() +
                      " check s/flood.toml >bg.out 2>&1 &) && while [ ! -e s/wrote ]; do sleep "
                      "0.02; done; sleep 0.5",
                  dir_.path());
  struct stat st {};
  const fs::path out = dir_ / "reports" / "flood" / "cases" / "flood" / "stdout.txt";
  ASSERT_EQ(::stat(out.c_str(), &st), 0);
  EXPECT_EQ(st.st_size, 300000000);                       // every byte counted
  EXPECT_LT(st.st_blocks * 512, std::int64_t{16} << 20);  // but not kept on disk
  std::ofstream(dir_ / "s" / "seen") << "";
  for (int i = 0; i < 500 && read_text(dir_ / "bg.out").find("1 case:") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_TRUE(
      read_text(out).starts_with("[aosuite: 300000000 bytes written; the last 65536 kept]"));
}

// Case fields go into the argv as they are; inside `sh -c` they are shell-quoted, so a field
// is never shell syntax.
TEST_F(ImageCases, PlaceholdersAreArgumentsNeverShellText) {
  std::ofstream(dir_ / "s" / "q.toml") << R"(
[[case]]
name = "quoted"
params = { label = "$(touch pwned); 'x' \"y\"", n = 3 }
command = ["sh", "-c", "printf '%s|%s' {label} {n} > {suite_dir}/label.txt && ls -A > {suite_dir}/ls.txt && cp {suite_dir}/red.png {out}/x.png"]
outputs = ["x.png"]
)";
  const test::Outcome r = aosuite("check s/q.toml");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;  // NEW
  EXPECT_FALSE(fs::exists(dir_ / "pwned"));
  EXPECT_EQ(read_text(dir_ / "s" / "ls.txt"), "");  // nothing was run in {out}, its folder
  EXPECT_EQ(read_text(dir_ / "s" / "label.txt"), "$(touch pwned); 'x' \"y\"|3");
  const auto results = nlohmann::json::parse(read_text(dir_ / "reports" / "q" / "results.json"));
  EXPECT_EQ(results["cases"][0]["params"]["n"], 3);  // typed, not "3"

  std::ofstream(dir_ / "s" / "bad.toml") << R"(
[[case]]
name = "bad"
command = ["sh", "{nope}"]
outputs = ["x.png"]
)";
  const test::Outcome bad = aosuite("check s/bad.toml");
  EXPECT_EQ(bad.rc, 2);
  EXPECT_NE(bad.err.find("s/bad.toml:4:"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("unknown placeholder '{nope}'"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir_ / "reports" / "bad"));
}

// Images already on disk are gated the same way.
TEST_F(ImageCases, FilesOnDiskAreGatedLikeRenders) {
  fs::create_directories(dir_ / "s" / "out");
  fs::copy_file(dir_ / "s" / "red.png", dir_ / "s" / "out" / "a.png");
  std::ofstream(dir_ / "s" / "f.toml") << R"(
[[case]]
name = "disk"
files = ["out/a.png"]
[case.tolerance]
max_mismatch_percent = 10
max_channel_delta = 255
max_mean_shift = 255
max_mean_delta = 255
)";
  EXPECT_EQ(aosuite("check s/f.toml").rc, 1);
  EXPECT_EQ(aosuite("bless s/f.toml").rc, 0);
  EXPECT_TRUE(fs::exists(dir_ / "s" / "goldens" / "f" / "disk" / "a.png"));
  EXPECT_EQ(aosuite("check s/f.toml").rc, 0);
  cv::Mat m = read_png_rgba8(dir_ / "s" / "out" / "a.png");
  m.at<cv::Vec4b>(0, 0) = {0, 0, 255, 255};  // 1 of 48 pixels: within 10 %
  write_png_rgba8(dir_ / "s" / "out" / "a.png", m);
  test::Outcome r = aosuite("check s/f.toml");
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("2.08%"), std::string::npos) << r.out;
  fs::copy_file(dir_ / "s" / "green.png", dir_ / "s" / "out" / "a.png",
                fs::copy_options::overwrite_existing);
  EXPECT_EQ(aosuite("check s/f.toml").rc, 1);
  std::ofstream(dir_ / "s" / "out" / "a.png", std::ios::trunc) << "not a png";
  r = aosuite("check s/f.toml");
  EXPECT_EQ(r.rc, 2) << r.out;
  EXPECT_NE(r.out.find("ERROR disk"), std::string::npos) << r.out;
}

// A report folder is one run's truth: `bless` (and a run killed before it saved cache.json)
// replaces a case's images there without touching the cache, and a later check whose input
// hash matches the cache must not take those images for its own. Reproduces issue 29's false
// PASS: A checked, B blessed, A checked again.
TEST_F(ImageCases, ImagesReplacedSinceTheCacheWasWrittenAreNotReused) {
  fs::create_directories(dir_ / "s" / "out");
  const fs::path shot = dir_ / "s" / "out" / "a.png";
  std::ofstream(dir_ / "s" / "f.toml") << "[[case]]\nname = \"disk\"\nfiles = [\"out/a.png\"]\n";
  const auto show = [&](const char* png) {
    fs::copy_file(dir_ / "s" / png, shot, fs::copy_options::overwrite_existing);
  };
  show("red.png");
  ASSERT_EQ(aosuite("bless s/f.toml").rc, 0);
  ASSERT_EQ(aosuite("check s/f.toml").rc, 0);
  show("green.png");
  ASSERT_EQ(aosuite("bless s/f.toml").rc, 0);  // goldens: green; the report's image: green
  show("red.png");
  test::Outcome r = aosuite("check s/f.toml");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("FAIL  disk"), std::string::npos) << r.out;
  // The same after the report's image is swapped by hand.
  fs::copy_file(dir_ / "s" / "green.png", dir_ / "reports" / "f" / "cases" / "disk" / "a.png",
                fs::copy_options::overwrite_existing);
  r = aosuite("check s/f.toml");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;

  // Approving from the report takes only the image the report judged: one replaced since (by
  // hand, a later or a killed run) or a link is refused, and the golden stays.
  const fs::path reported = dir_ / "reports" / "f" / "cases" / "disk" / "a.png";
  const auto golden = read_file(dir_ / "s" / "goldens" / "f" / "disk" / "a.png");
  fs::copy_file(dir_ / "s" / "green.png", reported, fs::copy_options::overwrite_existing);
  r = aosuite("bless s/f.toml --failed --report reports/f");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("not the image the report judged"), std::string::npos)
      << r.out << r.err;
  fs::remove(reported);
  fs::create_symlink(dir_ / "s" / "red.png", reported);
  r = aosuite("bless s/f.toml --failed --report reports/f");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE((r.out + r.err).find("not a regular file"), std::string::npos) << r.out << r.err;
  EXPECT_EQ(read_file(dir_ / "s" / "goldens" / "f" / "disk" / "a.png"), golden);
}

// A case's goldens change all or nothing. Two sets of two images, a small one and a large one;
// bless of the other set fails while writing the large one (ulimit -f), or is killed at
// staggered moments: each time, the case's goldens are all of one set.
TEST_F(ImageCases, ACasesGoldensAreReplacedAllOrNothing) {
  fs::create_directories(dir_ / "s" / "shots");
  std::ofstream(dir_ / "s" / "two.toml")
      << "[[case]]\nname = \"two\"\nfiles = [\"shots/a.png\", \"shots/b.png\"]\n";
  std::map<std::string, std::vector<unsigned char>> set[2];
  for (int k = 0; k < 2; ++k) {
    cv::Mat noise(512, 512, CV_8UC4);
    cv::randu(noise, cv::Scalar::all(0), cv::Scalar::all(256));  // incompressible: ~1 MB
    for (const auto& [name, img] :
         {std::pair{"a", flat(8, 6, {k ? 0.0 : 255.0, k ? 255.0 : 0.0, 0, 255})},
          std::pair{"b", noise}}) {
      const fs::path f = dir_ / "s" / fmt::format("{}{}.png", name, k);
      write_png_rgba8(f, img);
      set[k][name] = read_file(f);
    }
  }
  const auto show = [&](int k) {
    for (const char* name : {"a", "b"}) {
      fs::copy_file(dir_ / "s" / fmt::format("{}{}.png", name, k),
                    dir_ / "s" / "shots" / fmt::format("{}.png", name),
                    fs::copy_options::overwrite_existing);
    }
  };
  const fs::path goldens = dir_ / "s" / "goldens" / "two" / "two";
  // Which set the goldens are: -1 for a mix (or anything else).
  const auto which = [&] {
    for (int k = 0; k < 2; ++k) {
      if (read_file(goldens / "a.png") == set[k]["a"] &&
          read_file(goldens / "b.png") == set[k]["b"])
        return k;
    }
    return -1;
  };
  show(0);
  ASSERT_EQ(aosuite("bless s/two.toml").rc, 0);
  ASSERT_EQ(which(), 0);
  show(1);
  // a.png (100 bytes) fits under 64 KiB, b.png does not: the bless fails after writing a.png.
  test::Outcome r = aosuite("bless s/two.toml", "ulimit -f 128;");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("File too large"), std::string::npos) << r.out << r.err;
  EXPECT_EQ(which(), 0);
  for (int i = 0; i < 12; ++i) {
    show(1 - which());
    test::run_shell("cd " + dir_.path().string() + " && (" + aosuite_bin() +
                        fmt::format(" bless s/two.toml >/dev/null 2>&1 & p=$!; sleep {:.3f}; "
                                    "kill -9 $p; wait $p)",
                                    i * 0.008),
                    dir_.path());
    ASSERT_NE(which(), -1) << "a mix of both sets after a kill at step " << i;
  }
  // What killed blesses left beside the case is removed by the next bless.
  show(1 - which());
  ASSERT_EQ(aosuite("bless s/two.toml").rc, 0);
  for (const auto& e : fs::directory_iterator(goldens.parent_path()))
    EXPECT_EQ(e.path().filename(), "two") << "left behind: " << e.path();
}

// Folder mode, as reg-cli: two folders of PNGs paired by relative path; changed, new and
// deleted images; bless makes the expected folder match.
// On GitHub Actions (GITHUB_ACTIONS=true) check speaks the CI's language: an ::error line per
// failing case on the actual image, and a step-summary table appended to $GITHUB_STEP_SUMMARY;
// --json keeps stdout JSON (the summary is still written); elsewhere neither appears.
TEST_F(ImageCases, OnGitHubActionsFailuresAreAnnotatedAndSummarised) {
  for (const char* d : {"actual", "expected"}) fs::create_directories(dir_ / d);
  fs::copy_file(dir_ / "s" / "green.png", dir_ / "actual" / "changed.png");
  fs::copy_file(dir_ / "s" / "red.png", dir_ / "expected" / "changed.png");
  fs::copy_file(dir_ / "s" / "red.png", dir_ / "actual" / "same.png");
  fs::copy_file(dir_ / "s" / "red.png", dir_ / "expected" / "same.png");
  const std::string folders = "check --actual actual --expected expected --report rep";
  std::ofstream(dir_ / "summary.md") << "earlier step\n";
  const std::string gh = "GITHUB_ACTIONS=true GITHUB_STEP_SUMMARY=summary.md";
  test::Outcome r = aosuite(folders, gh);
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("::error file=actual/changed.png,title=aosuite FAIL changed.png::"
                       "changed.png: image: mismatch 50.00%25 (allowed 0%25)"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("same.png::"), std::string::npos) << r.out;  // passing: no annotation
  const std::string summary = read_text(dir_ / "summary.md");
  EXPECT_EQ(summary.rfind("earlier step\n### aosuite: folder — 2 cases: 1 passed, 1 failed", 0), 0u)
      << summary;
  EXPECT_NE(summary.find("| changed.png | FAIL | image: 255 @ (0, 0) | image: mismatch 50.00% "
                         "(allowed 0%)"),
            std::string::npos)
      << summary;
  EXPECT_NE(summary.find("/rep/index.html` ("), std::string::npos) << summary;  // and its size
  EXPECT_NE(summary.find("bless --actual actual --expected expected --failed --report rep`"),
            std::string::npos)
      << summary;

  r = aosuite(folders + " --json", gh);
  EXPECT_EQ(r.out.find("::error"), std::string::npos) << r.out;
  EXPECT_NE(read_text(dir_ / "summary.md").find("earlier step\n### aosuite"), std::string::npos);
  r = aosuite(folders);
  EXPECT_EQ(r.out.find("::error"), std::string::npos) << r.out;
  // Asked for by name elsewhere; turned off on GitHub.
  r = aosuite(folders + " --annotations github");
  EXPECT_NE(r.out.find("::error file=actual/changed.png"), std::string::npos) << r.out;
  r = aosuite(folders + " --annotations none", gh);
  EXPECT_EQ(r.out.find("::error"), std::string::npos) << r.out;
  // report merge speaks too.
  const std::string shard = "check --actual actual --expected expected --shard ";
  aosuite(shard + "0/2 --report s0");
  aosuite(shard + "1/2 --report s1");
  r = aosuite("report merge --out merged s0 s1 --annotations github");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("::error file=actual/changed.png,title=aosuite FAIL changed.png::"),
            std::string::npos)
      << r.out;
}

// A printed command runs as printed: `aosuite` when the shell found it on PATH, else the path
// it was started by, made absolute and quoted (a folder with a space in its name).
TEST_F(ImageCases, PrintedCommandsRunAsPrintedWhicheverWayAosuiteWasStarted) {
  for (const char* d : {"actual", "expected", "my tools"}) fs::create_directories(dir_ / d);
  fs::copy_file(dir_ / "s" / "green.png", dir_ / "actual" / "changed.png");
  fs::copy_file(dir_ / "s" / "red.png", dir_ / "expected" / "changed.png");
  const std::string folders = " check --actual actual --expected expected --report rep";
  const std::string accept =
      " bless --actual actual --expected expected --filter '^changed\\.png$'";
  test::Outcome r = test::run_shell(
      "cd " + dir_.path().string() + " && PATH=" + fs::path(aosuite_bin()).parent_path().string() +
          ":$PATH aosuite" + folders,
      dir_.path());
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("to accept changed.png: aosuite" + accept + "\n"), std::string::npos)
      << r.out;

  fs::create_symlink(aosuite_bin(), dir_ / "my tools" / "aosuite");
  r = test::run_shell("cd " + dir_.path().string() + " && './my tools/aosuite'" + folders,
                      dir_.path());
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  const std::string printed = "'" + (dir_ / "my tools" / "aosuite").string() + "'" + accept;
  EXPECT_NE(r.out.find("to accept changed.png: " + printed + "\n"), std::string::npos) << r.out;
  r = test::run_shell("cd / && cd " + dir_.path().string() + " && " + printed, dir_.path());
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_EQ(read_file(dir_ / "expected" / "changed.png"), read_file(dir_ / "s" / "green.png"));
}

TEST_F(ImageCases, FolderModeReportsChangedNewAndDeletedAndBlessAcceptsThem) {
  for (const char* d : {"actual/sub", "expected/sub", "empty1", "empty2"}) {
    fs::create_directories(dir_ / d);
  }
  const fs::path red = dir_ / "s" / "red.png", green = dir_ / "s" / "green.png";
  for (const auto& [from, to] :
       std::vector<std::pair<fs::path, const char*>>{{red, "actual/same.png"},
                                                     {red, "expected/same.png"},
                                                     {red, "actual/sub/deep one.png"},
                                                     {red, "expected/sub/deep one.png"},
                                                     {green, "actual/changed.png"},
                                                     {red, "expected/changed.png"},
                                                     {green, "actual/new.png"},
                                                     {red, "expected/gone.png"}}) {
    fs::copy_file(from, dir_ / to);
  }
  std::ofstream(dir_ / "actual" / "notes.txt") << "not an image";
  // EXR files are paired too, and without a float gate compared sample for sample.
  test::write_exr(dir_ / "actual" / "depth.exr", 2, 1, {"Y"}, {0.5f, 1.0f});
  test::write_exr(dir_ / "expected" / "depth.exr", 2, 1, {"Y"}, {0.5f, 2.0f});
  test::write_exr(dir_ / "actual" / "sub" / "same.exr", 2, 1, {"Y"}, {0.5f, 1.0f});
  fs::copy_file(dir_ / "actual" / "sub" / "same.exr", dir_ / "expected" / "sub" / "same.exr");
  test::Outcome r = aosuite("check --actual actual --expected expected --report rep --junit j.xml");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("7 images: 3 unchanged, 2 changed, 1 new, 1 deleted, 0 errors"),
            std::string::npos)
      << r.out;
  // The summary gives the report's size, what a CI uploads: its files, counted here.
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "rep")) files += e.is_regular_file();
  EXPECT_NE(r.out.find("Report: rep/index.html (" + std::to_string(files) + " files, "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("sub__deep_one.png  sub/deep one.png"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("deleted: only in the expected folder"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("aosuite bless --actual actual --expected expected --filter "
                       "'^(changed\\.png|depth\\.exr|gone\\.png|new\\.png)$'"),
            std::string::npos)
      << r.out;
  const auto results = nlohmann::json::parse(read_text(dir_ / "rep" / "results.json"));
  EXPECT_EQ(results["cases"].size(), 7u);
  for (const auto& c : results["cases"]) EXPECT_EQ(c["deleted"], c["id"] == "gone.png") << c["id"];
  EXPECT_NE(r.out.find("the float images differ"), std::string::npos) << r.out;
  EXPECT_EQ(results["cases"][0]["kind"], "folder");
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "index.html"));
  EXPECT_TRUE(fs::exists(dir_ / "rep" / "cases" / "changed.png" / "diff_image.png"));
  EXPECT_NE(read_text(dir_ / "j.xml").find("tests=\"7\" failures=\"4\""), std::string::npos);
  const auto same_time = fs::last_write_time(dir_ / "expected" / "same.png");

  // Accept from the report: changed and new copied, the deleted one removed, the rest as it was.
  r = aosuite("bless --actual actual --expected expected --failed --report rep");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("4 of 4 cases blessed"), std::string::npos) << r.out;
  EXPECT_EQ(read_file(dir_ / "expected" / "depth.exr"), read_file(dir_ / "actual" / "depth.exr"));
  EXPECT_EQ(read_file(dir_ / "expected" / "changed.png"), read_file(green));
  EXPECT_EQ(read_file(dir_ / "expected" / "new.png"), read_file(green));
  EXPECT_FALSE(fs::exists(dir_ / "expected" / "gone.png"));
  EXPECT_EQ(fs::last_write_time(dir_ / "expected" / "same.png"), same_time);
  r = aosuite("check --actual actual --expected expected --report rep");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("6 images: 6 unchanged, 0 changed, 0 new, 0 deleted"), std::string::npos)
      << r.out;

  // Plain bless (no report) accepts what the folders hold now.
  fs::copy_file(red, dir_ / "actual" / "new.png", fs::copy_options::overwrite_existing);
  EXPECT_EQ(aosuite("check --actual actual --expected expected").rc, 1);
  r = aosuite("bless --actual actual --expected expected");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("1 of 6 cases blessed"), std::string::npos) << r.out;
  EXPECT_EQ(read_file(dir_ / "expected" / "new.png"), read_file(red));

  // Nothing to compare is not green; half a folder pair is a one-line error.
  for (const char* bad : {"check --actual empty1 --expected empty2", "check --actual actual",
                          "check s/t.toml --actual actual --expected expected",
                          "check --actual nowhere --expected expected",
                          "bless --actual actual --expected expected --variant x"}) {
    r = aosuite(bad);
    EXPECT_EQ(r.rc, 2) << bad << "\n" << r.out << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << "\n" << r.err;
  }
}

// --json: one object per case as it finishes, then a summary; `scenes --json` likewise.
// No text in a name or in a command's stderr can blank the report: `<!--<script>` in a script
// element's data sends Chromium's parser into a state where `</script>` no longer ends it, and
// the table drew no row. The page is checked as Chromium builds it.
TEST_F(ImageCases, MarkupInNamesAndStderrCannotEndTheReportsData) {
  const std::string payload = "<!--<script>";
  for (const char* d : {"actual", "expected"}) fs::create_directories(dir_ / d);
  const fs::path red = dir_ / "s" / "red.png", green = dir_ / "s" / "green.png";
  fs::copy_file(green, dir_ / "actual" / (payload + "a.png"));
  fs::copy_file(red, dir_ / "expected" / (payload + "a.png"));
  fs::copy_file(green, dir_ / "actual" / "b.png");
  fs::copy_file(red, dir_ / "expected" / "b.png");
  test::Outcome r = aosuite("check --actual actual --expected expected --report rep");
  ASSERT_EQ(r.rc, 1) << r.out << r.err;
  const std::string html = read_text(dir_ / "rep" / "index.html");
  const std::string tag = "<script type=\"application/json\" id=data>";
  const std::size_t d0 = html.find(tag) + tag.size();
  const std::string data = html.substr(d0, html.find("</script>", d0) - d0);
  EXPECT_EQ(data.find('<'), std::string::npos) << data;
  EXPECT_NE(nlohmann::json::parse(data).dump().find(payload), std::string::npos);
  r = test::run_shell("chromium --headless --no-sandbox --disable-gpu --dump-dom 'file://" +
                          (dir_ / "rep" / "index.html").string() + "'",
                      dir_.path());
  ASSERT_EQ(r.rc, 0) << r.err;
  std::size_t rows = 0;
  for (std::size_t at = 0; (at = r.out.find("<tr data-i=\"", at)) != std::string::npos; ++at)
    ++rows;
  EXPECT_EQ(rows, 2u) << r.out;
  EXPECT_NE(r.out.find("&lt;!--&lt;script&gt;a.png"), std::string::npos) << r.out;
}

TEST_F(ImageCases, JsonOutputIsOneObjectPerCaseThenASummary) {
  std::ofstream(dir_ / "s" / "t.toml", std::ios::app) << R"(
[[case]]
name = "disk"
files = ["red.png"]
params = { quality = 0.75, n = 2, label = "x" }
)";
  const test::Outcome r = aosuite("check s/t.toml --json");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  std::vector<nlohmann::json> lines;
  std::stringstream in(r.out);
  for (std::string line; std::getline(in, line);) {
    ASSERT_NO_THROW(lines.push_back(nlohmann::json::parse(line))) << line;
  }
  ASSERT_EQ(lines.size(), 3u) << r.out;
  for (int i : {0, 1}) {
    EXPECT_EQ(lines[i]["type"], "case");
    EXPECT_EQ(lines[i]["status"], "NEW");
  }
  const nlohmann::json& disk = lines[0]["id"] == "disk" ? lines[0] : lines[1];
  EXPECT_EQ(disk["params"]["quality"], 0.75);
  EXPECT_EQ(disk["params"]["n"], 2);
  EXPECT_EQ(disk["params"]["label"], "x");
  EXPECT_EQ(lines[2]["type"], "summary");
  EXPECT_EQ(lines[2]["new"], 2);
  EXPECT_EQ(lines[2]["exit_status"], 1);
  EXPECT_EQ(lines[2]["bless_command"], aosuite_bin() + " bless s/t.toml --filter '^(chart|disk)$'");
  EXPECT_EQ(lines[2]["approve_failed"],
            aosuite_bin() + " bless s/t.toml --failed --report reports/t");

  if (!has_ao_bench()) return;  // `scenes` belongs to the AO bench
  const test::Outcome scenes = aosuite("scenes --json");
  EXPECT_EQ(scenes.rc, 0) << scenes.err;
  const nlohmann::json j = nlohmann::json::parse(scenes.out);
  bool corner = false;
  for (const nlohmann::json& s : j["scenes"]) {
    if (s["name"] == "corner") {
      corner = true;
      EXPECT_EQ(s["kind"], "built-in");
      EXPECT_FALSE(s["views"].empty());
      EXPECT_TRUE(s["views"][0]["eye"].is_array());
      EXPECT_TRUE(s["views"][0]["fovy_degrees"].is_number());
    }
  }
  EXPECT_TRUE(corner) << scenes.out;
}

// --retries: a case that fails and then passes is FLAKY, apart from pass and fail, in the
// console, results.json and JUnit; the run is green. Without retries it fails.
TEST_F(ImageCases, RetriesReportFlakyCasesApart) {
  // Draws the wrong chart on every other run.
  std::ofstream(dir_ / "s" / "t.toml", std::ios::app) << R"SH(
[[case]]
name = "wobbly"
command = ["sh", "-c", "if [ -e {suite_dir}/odd ]; then rm {suite_dir}/odd; cp {suite_dir}/red.png {out}/w.png; else touch {suite_dir}/odd; cp {suite_dir}/green.png {out}/w.png; fi"]
outputs = ["w.png"]
)SH";
  std::ofstream(dir_ / "s" / "odd") << "";
  ASSERT_EQ(aosuite("bless s/t.toml").rc, 0);  // wobbly's golden is red
  test::Outcome r = aosuite("check s/t.toml --no-reuse");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;  // green this time
  fs::remove(dir_ / "s" / "odd");        // green first, then red
  r = aosuite("check s/t.toml --no-reuse --retries 2 --junit j.xml");
  EXPECT_EQ(r.rc, 0) << r.out << r.err;  // red on the second attempt
  EXPECT_NE(r.out.find("FLAKY wobbly"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(2 attempts)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 cases: 1 passed, 0 failed, 0 new, 0 errors, 1 flaky"), std::string::npos)
      << r.out;
  const auto results = nlohmann::json::parse(read_text(dir_ / "reports" / "t" / "results.json"));
  for (const nlohmann::json& c : results["cases"]) {
    if (c["id"] != "wobbly") continue;
    EXPECT_EQ(c["status"], "FLAKY");
    EXPECT_EQ(c["attempts"], 2);
    EXPECT_NE(c["message"].get<std::string>().find("failed, then passed on attempt 2"),
              std::string::npos);
    // The failing attempt's images are kept beside the passing one's, and named in the results.
    ASSERT_EQ(c["failed_attempts"].size(), 1u) << c;
    const nlohmann::json& first = c["failed_attempts"][0];
    EXPECT_EQ(first["status"], "FAIL");
    EXPECT_EQ(first["files"]["w"], "wobbly/attempt1_w.png");
    EXPECT_EQ(first["files"]["diff:w"], "wobbly/attempt1_diff_w.png");
    EXPECT_EQ(first["files"]["golden:w"], "wobbly/attempt1_golden_w.png");
    const fs::path folder = dir_ / "reports" / "t" / "cases" / "wobbly";
    EXPECT_EQ(read_file(folder / "attempt1_w.png"), read_file(dir_ / "s" / "green.png"));
    EXPECT_EQ(read_file(folder / "w.png"), read_file(dir_ / "s" / "red.png"));
  }
  const std::string junit = read_text(dir_ / "j.xml");
  EXPECT_NE(junit.find("failures=\"0\""), std::string::npos) << junit;
  EXPECT_NE(junit.find("<flakyFailure"), std::string::npos) << junit;
  // Retries never hide a case that keeps failing.
  std::ofstream(dir_ / "s" / "colour.txt", std::ios::trunc) << "green";
  r = aosuite("check s/t.toml --retries 2");
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_NE(r.out.find("FAIL  chart"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(3 attempts)"), std::string::npos) << r.out;
}

// The report at scale: images as files beside index.html (thumbnails for big ones), failures
// first and passes by margin, and the command for the cases selected in the page blesses
// exactly them from the report's images.
TEST_F(ImageCases, TheReportOrdersLinksAndApprovesWhatIsSelected) {
  fs::create_directories(dir_ / "s" / "shots");
  cv::Mat big(300, 400, CV_8UC4, cv::Scalar(200, 100, 50, 255));
  write_png_rgba8(dir_ / "s" / "shots" / "big.png", big);
  std::string suite = R"(
[defaults.tolerance]
max_mismatch_percent = 60
max_channel_delta = 255
max_mean_shift = 255
max_mean_delta = 255
[[case]]
name = "big"
files = ["shots/big.png"]
)";
  // a: fails; b: passes with 50 % changed (a near miss); c: passes identical; d: fails.
  for (const char* name : {"a", "b", "c", "d"}) {
    fs::copy_file(dir_ / "s" / "red.png", dir_ / "s" / "shots" / (std::string(name) + ".png"));
    suite +=
        std::string("[[case]]\nname = \"") + name + "\"\nfiles = [\"shots/" + name + ".png\"]\n";
  }
  std::ofstream(dir_ / "s" / "r.toml") << suite;
  ASSERT_EQ(aosuite("bless s/r.toml").rc, 0);
  for (const char* name : {"a", "d"}) {
    write_png_rgba8(dir_ / "s" / "shots" / (std::string(name) + ".png"),
                    flat(8, 6, {0, 0, 255, 255}));
  }
  fs::copy_file(dir_ / "s" / "green.png", dir_ / "s" / "shots" / "b.png",
                fs::copy_options::overwrite_existing);
  test::Outcome r = aosuite("check s/r.toml");
  ASSERT_EQ(r.rc, 1) << r.out << r.err;
  const fs::path report = dir_ / "reports" / "r";
  const std::string html = read_text(report / "index.html");
  EXPECT_EQ(html.find("iVBOR"), std::string::npos);  // images are files, not embedded PNGs
  EXPECT_EQ(html.find("http"), std::string::npos);   // nothing from the network
  // Failures first, then passes by margin: b (10 % left) before c and big (60 % left).
  const std::string tag = "<script type=\"application/json\" id=data>";
  const std::size_t d0 = html.find(tag) + tag.size();
  const auto data = nlohmann::json::parse(html.substr(d0, html.find("</script>", d0) - d0));
  std::vector<std::string> order;
  for (const nlohmann::json& c : data) order.push_back(c["id"]);
  ASSERT_EQ(order.size(), 5u);
  EXPECT_EQ(std::set<std::string>(order.begin(), order.begin() + 2),
            (std::set<std::string>{"a", "d"}));
  EXPECT_EQ(order[2], "b") << html;
  // The big image gets a thumbnail; small ones are their own.
  const cv::Mat thumb = read_png_rgba8(report / "cases" / "big" / "thumb_big.png");
  EXPECT_LE(thumb.cols, 160);
  EXPECT_LE(thumb.rows, 120);
  for (const nlohmann::json& c : data) {
    EXPECT_EQ(c["thumb"],
              "cases/" + c["id"].get<std::string>() + "/" +
                  (c["id"] == "big" ? "thumb_big.png" : c["id"].get<std::string>() + ".png"));
  }

  // In the browser: the page is ready, the first failure is open, every image resolves to a
  // file beside it; selecting a and b (#select=) gives one command for exactly them; n moves
  // to the next failure.
  r = test::run_shell("chromium --headless --no-sandbox --disable-gpu --dump-dom 'file://" +
                          (report / "index.html").string() + "#select=a,b'",
                      dir_.path());
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_NE(r.out.find("data-ready-ms=\""), std::string::npos);
  EXPECT_NE(r.out.find("<h2 id=\"a\">a <span class=\"FAIL\">FAIL</span>"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("class=\"slider\""), std::string::npos);
  EXPECT_NE(r.out.find("src=\"cases/a/golden_a.png\""), std::string::npos);
  const std::string begin = "<code id=\"command\">";
  const std::size_t c0 = r.out.find(begin);
  ASSERT_NE(c0, std::string::npos) << r.out;
  const std::string command =
      r.out.substr(c0 + begin.size(), r.out.find("</code>", c0) - c0 - begin.size());
  EXPECT_EQ(command,
            aosuite_bin() +
                " bless s/r.toml --from-report --report reports/r --force --filter '^(a|b)$'");
  // With the first failure's panel open at 1280x720, nothing covers the approve bar's copy
  // button (the panel once did).
  for (const char* size : {"1280,720", "2200,1200"}) {
    const test::Outcome laid_out = test::run_shell(
        std::string("chromium --headless --no-sandbox --disable-gpu --window-size=") + size +
            " --dump-dom 'file://" + (report / "index.html").string() + "'",
        dir_.path());
    EXPECT_NE(laid_out.out.find("class=\"panel\""), std::string::npos) << size;
    EXPECT_NE(laid_out.out.find("data-copy-covered=\"false\""), std::string::npos)
        << size << laid_out.out.substr(0, 300);
  }
  const test::Outcome keys =
      test::run_shell("chromium --headless --no-sandbox --disable-gpu --dump-dom 'file://" +
                          (report / "index.html").string() + "#keys=n'",
                      dir_.path());
  EXPECT_NE(keys.out.find("<h2 id=\"d\">d <span class=\"FAIL\">FAIL</span>"), std::string::npos)
      << keys.out;

  // The copied command approves a and b from the report's images; d stays failing.
  const auto c_before = read_file(dir_ / "s" / "goldens" / "r" / "c" / "c.png");
  r = test::run_shell("cd " + dir_.path().string() + " && " + command, dir_.path());
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("2 of 2 cases blessed"), std::string::npos) << r.out;
  EXPECT_EQ(read_file(dir_ / "s" / "goldens" / "r" / "c" / "c.png"), c_before);
  r = aosuite("check s/r.toml");
  EXPECT_EQ(r.rc, 1) << r.out;
  EXPECT_NE(r.out.find("4 passed, 1 failed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAIL  d"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace aosuite

// `aosuite compare` as a user runs it: exit codes, messages, and nothing written on error.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
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

// A shell command's exit status, stderr, peak resident memory and wall time, measured on that
// process alone (wait4). Commands end by exec-ing aosuite, so the peak is aosuite's.
struct Measured {
  int rc;
  std::string err;
  long max_rss_mb;
  double seconds;
};

Measured run_measured(const test::TempDir& dir, const std::string& command) {
  const std::string err_file = (dir / "measured_stderr.txt").string();
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string cmd = "exec 2>'" + err_file + "'; " + command;
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  std::stringstream err;
  err << std::ifstream(err_file).rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, err.str(), usage.ru_maxrss / 1024,
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

// Deflate's fixed-Huffman block, written a bit at a time (least significant first).
class BitWriter {
 public:
  void bits(std::uint32_t value, int n) {  // extra bits and header fields
    for (int i = 0; i < n; ++i) put((value >> i) & 1);
  }
  void code(std::uint32_t code, int n) {  // Huffman codes go most significant bit first
    for (int i = n - 1; i >= 0; --i) put((code >> i) & 1);
  }
  test::Bytes finish() {
    if (used_) out_.push_back(acc_);
    return std::move(out_);
  }

 private:
  void put(std::uint32_t bit) {
    acc_ = static_cast<unsigned char>(acc_ | bit << used_);
    if (++used_ == 8) out_.push_back(acc_), acc_ = 0, used_ = 0;
  }
  test::Bytes out_;
  unsigned char acc_ = 0;
  int used_ = 0;
};

// A zlib stream of n zero bytes, n > 258: a literal 0 then copies of 258 bytes at distance 1,
// 13 bits each, so 1 GiB takes about 6.5 MB (zlib would take seconds to write it).
test::Bytes zeros_stream(std::uint64_t n) {
  BitWriter w;
  w.bits(1, 1), w.bits(1, 2);  // the final block, fixed Huffman codes
  w.code(0x30, 8);             // literal 0
  std::uint64_t left = n - 1;
  auto copy = [&](std::uint32_t len) {  // lengths 3..10 are codes 257..264, 258 is 285
    if (len == 258) {
      w.code(0xc5, 8);
    } else {
      w.code(len - 3 + 1, 7);
    }
    w.code(0, 5);  // distance 1
  };
  for (; left >= 258 + 3; left -= 258) copy(258);
  while (left >= 3) {
    const std::uint32_t len = static_cast<std::uint32_t>(std::min<std::uint64_t>(left, 10));
    copy(len);
    left -= len;
  }
  for (; left > 0; --left) w.code(0x30, 8);
  w.code(0, 7);  // end of block
  test::Bytes z = {0x78, 0x01};
  const test::Bytes body = w.finish();
  z.insert(z.end(), body.begin(), body.end());
  test::put_u32(z, static_cast<std::uint32_t>((n % 65521) << 16 | 1));  // Adler-32 of zeros
  return z;
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
  // one pixel of 600 is 0.1666 %: within a 0.2 % threshold, but the threshold names only the
  // mismatch: the channel limit stays in force until it is lifted by name
  EXPECT_EQ(run(dir_, path("a.png") + " " + path("b.png") + " --threshold 0.2").rc, 1);
  EXPECT_EQ(run(dir_, path("a.png") + " " + path("b.png") +
                          " --threshold 0.2 --limit max_channel_delta=255")
                .rc,
            0);
  EXPECT_EQ(run(dir_, path("a.png") + " " + path("small.png") + " --threshold 100").rc, 1);
}

TEST_F(CliCompare, JsonHasResemblesKeysInOrder) {
  const Outcome r = run(dir_, path("a.png") + " " + path("b.png") + " --json");
  const auto j = nlohmann::ordered_json::parse(r.out);
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  // Resemble.js's own keys first, in its order; then what the exit status says and what kind
  // of change it saw.
  EXPECT_EQ(keys, (std::vector<std::string>{"misMatchPercentage", "rawMisMatchPercentage",
                                            "isSameDimensions", "dimensionDifference", "diffBounds",
                                            "analysisTime", "verdict", "failed_gates", "changes"}));
  EXPECT_EQ(j["verdict"], "different");
  ASSERT_EQ(j["changes"].size(), 1u);  // one changed pixel: scattered, so noise
  EXPECT_EQ(j["changes"][0]["pixels"], 1);
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

// Every bad option: exit 2, one line "aosuite compare: <problem>" naming it, nothing written.
TEST_F(CliCompare, BadOptionsAreOneLineAndExitTwo) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--threshold nan", "--threshold 'nan'"},
      {"--threshold -1", "--threshold '-1' is out of range"},
      {"--threshold 101", "--threshold '101' is out of range"},
      {"--threshold 1e-320", "--threshold '1e-320' is out of range"},
      {"--threshold 1e999", "--threshold '1e999' is out of range"},
      {"--threshold 5x", "--threshold '5x' is not a number"},
      {"--error-type bogus", "--error-type 'bogus' is unknown"},
      {R"(--tolerance '{"red":4}')", "--tolerance needs --mode"},
      {R"(--mode default --tolerance '{"red":4}')", "--tolerance needs --mode"},
      {"--transparency inf", "--transparency 'inf'"},
      {"--return-early-threshold nan", "--return-early-threshold 'nan'"},
      {"--bounding-box 1,2,nan,4", "'nan'"},
      {"--error-color 1,2,1e999", "out of range"},
      {"--memory-limit 0", "--memory-limit '0' is out of range"},
      {"--mode sideways", "unknown mode 'sideways'"},
      {"--no-such-option", "--no-such-option"},
  };
  for (const auto& [args, want] : cases) {
    const Outcome r =
        run(dir_, path("a.png") + " " + path("b.png") + " --diff " + path("out.png") + " " + args);
    EXPECT_EQ(r.rc, 2) << args;
    EXPECT_EQ(r.err.rfind("aosuite compare: ", 0), 0u) << args << ": " << r.err;
    EXPECT_NE(r.err.find(want), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "out.png")) << args;
  }
  // Without a second image: a usage error, one line.
  const Outcome one = run(dir_, path("a.png"));
  EXPECT_EQ(one.rc, 2);
  EXPECT_EQ(one.err, "aosuite compare: needs two images, or --batch FILE\n");
  // With a mode the tolerance is Resemble's: colour differences under it match Resemble's count,
  // and the channel limits, which it does not name, still hold until lifted by name.
  const std::string tolerated =
      path("a.png") + " " + path("b.png") + R"( --mode nothing --tolerance '{"red":255}')";
  EXPECT_EQ(run(dir_, tolerated).rc, 1);
  EXPECT_EQ(run(dir_, tolerated + " --limit max_channel_delta=255 --limit max_mean_shift=255 "
                                  "--limit max_mean_delta=255")
                .rc,
            0);
}

TEST_F(CliCompare, UnknownCommandIsNamed) {
  for (const char* args : {"foo", "foo a.png b.png", ""}) {
    const Outcome r = test::run_shell(std::string(AOSUITE_BIN) + " " + args, dir_.path());
    EXPECT_EQ(r.rc, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find("compare, check, bless, report, tolerances, render"), std::string::npos)
        << args << ": " << r.err;
    if (*args) {
      EXPECT_NE(r.err.find("unknown command 'foo'"), std::string::npos) << r.err;
    }
  }
}

// One rule decides `compare` and `check`: the same pair under the same limits fails for the same
// reasons, said in the same words (compare --json's failed_gates; folder mode's message in
// results.json), whichever limits fail: Resemble's, a gate's, both or neither.
TEST_F(CliCompare, CompareAndCheckGiveOneVerdict) {
  std::filesystem::create_directories(dir_ / "actual");
  std::filesystem::create_directories(dir_ / "expected");
  std::filesystem::copy_file(path("a.png"), dir_ / "expected" / "x.png");
  std::filesystem::copy_file(path("b.png"), dir_ / "actual" / "x.png");
  for (const char* mismatch : {"0", "1"}) {
    for (const char* rmse : {"0.0001", "1"}) {
      SCOPED_TRACE(fmt::format("mismatch {} rmse {}", mismatch, rmse));
      const std::string limits = fmt::format("--gate rmse.max={}", rmse);
      const Outcome c = run(dir_, fmt::format("{} {} --metric resemble --mode less --threshold {} "
                                              "--limit max_channel_delta=255 {} --json",
                                              path("a.png"), path("b.png"), mismatch, limits));
      const auto failed = nlohmann::json::parse(c.out)["failed_gates"];
      std::string said;
      for (const auto& f : failed) said += (said.empty() ? "" : "; ") + f.get<std::string>();
      const Outcome k = test::run_shell(
          fmt::format("cd {} && {} check --actual actual --expected expected --report r "
                      "--max-mismatch {} --max-channel-delta 255 {}",
                      dir_.path().string(), AOSUITE_BIN, mismatch, limits),
          dir_.path());
      EXPECT_EQ(c.rc, failed.empty() ? 0 : 1) << c.out;
      EXPECT_EQ(k.rc, c.rc) << k.out << k.err;
      std::ifstream results(dir_ / "r" / "results.json");
      const auto image = nlohmann::json::parse(results)["cases"][0]["images"][0];
      EXPECT_EQ(image.value("message", ""), said);
    }
  }
}

// A mistyped option is named as typed, with the nearest the command has; an extra argument is
// named as typed (CLI11 alone listed them reversed and suggested nothing). Built-in and library
// commands alike.
TEST_F(CliCompare, MistypedOptionsAreNamedWithASuggestion) {
  const std::string a = path("a.png"), b = path("b.png");
  const std::pair<std::string, std::string> cases[] = {
      {"compare --metrc flip " + a + " " + b,
       "aosuite compare: unknown option '--metrc'; did you mean '--metric'? (aosuite compare "
       "--help lists them)\n"},
      {"compare " + a + " " + b + " " + a + " " + b,
       "aosuite compare: unexpected argument '" + a +
           "' (aosuite compare --help lists what it takes)\n"},
      {"bless --faild --report r",
       "aosuite bless: unknown option '--faild'; did you mean "
       "'--failed'? (aosuite bless --help lists them)\n"},
      {"check --suit x.toml",
       "aosuite check: unknown option '--suit' (aosuite check --help "
       "lists them)\n"},
      {"compare -x " + a + " " + b,
       "aosuite compare: unknown option '-x' (aosuite compare --help lists them)\n"},
  };
  for (const auto& [args, message] : cases) {
    const Outcome r = test::run_shell(std::string(AOSUITE_BIN) + " " + args, dir_.path());
    EXPECT_EQ(r.rc, 2) << args;
    EXPECT_EQ(r.err, message) << args;
  }
}

// Pipes have no size (st_size 0): they are read to end-of-file.
TEST_F(CliCompare, ReadsPipesAndFifos) {
  const std::string bin = AOSUITE_BIN;
  EXPECT_EQ(test::run_shell(
                "cat " + path("a.png") + " | " + bin + " compare /dev/stdin " + path("a_copy.png"),
                dir_.path())
                .rc,
            0);
  const Outcome sub = test::run_shell(
      "bash -c '" + bin + " compare <(cat " + path("a.png") + ") " + path("b.png") + " --json'",
      dir_.path());
  EXPECT_EQ(sub.rc, 1) << sub.err;
  EXPECT_NE(sub.out.find(R"("misMatchPercentage":"0.17")"), std::string::npos) << sub.out;
  // A named FIFO whose writer is already waiting in its open. The writer holds no end of
  // this shell's output pipe, so a compare that failed before opening the FIFO ends the test
  // rather than leaving it waiting for the writer (as a crash at start-up once did).
  ASSERT_EQ(::mkfifo(path("fifo").c_str(), 0600), 0);
  EXPECT_EQ(test::run_shell("(timeout 60 cat " + path("a.png") + " > " + path("fifo") +
                                " &) >/dev/null 2>&1; timeout 60 " + bin + " compare " +
                                path("fifo") + " " + path("a_copy.png"),
                            dir_.path())
                .rc,
            0);
}

// A FIFO nobody writes to: opening it would block forever; it waits a bounded time for data.
TEST_F(CliCompare, FifoWithoutWriterIsAnErrorNotAHang) {
  ASSERT_EQ(::mkfifo(path("lonely").c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  const Outcome r = test::run_shell("AOSUITE_FIFO_WAIT_MS=300 timeout 20 " +
                                        std::string(AOSUITE_BIN) + " compare " + path("lonely") +
                                        " " + path("a.png") + " --diff " + path("out.png"),
                                    dir_.path());
  EXPECT_EQ(r.rc, 2) << "124 is the timeout: it hung";
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10);
  EXPECT_NE(r.err.find(path("lonely") + ": a FIFO with no data"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out.png"));
}

// A safety net against a runaway allocation. ASan reserves terabytes of address space for its
// shadow memory, so under it the limit would stop the process before it starts; the RSS
// bounds below still hold there. GCC says ASan is on with __SANITIZE_ADDRESS__, clang 14 only
// with __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define AOSUITE_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define AOSUITE_TEST_ASAN 1
#endif
#endif
#ifdef AOSUITE_TEST_ASAN
constexpr const char* kAddressLimit = "";
#else
constexpr const char* kAddressLimit = "ulimit -v 2000000; ";
#endif

// A file that claims 16384x16384 pixels with under a kilobyte of data fails at once, without
// allocating the gigabyte its header asks for.
TEST_F(CliCompare, TinyFileClaimingAHugeImageFailsWithoutAllocating) {
  test::write_bytes(
      dir_ / "claims.png",
      test::png_with_idat(16384, 16384, 8, 6, test::zlib_compress(test::Bytes(800, 0))));
  for (const char* mode : {"", " --mode antialiasing --diff "}) {
    const Measured m = run_measured(
        dir_, std::string(kAddressLimit) + "exec " + AOSUITE_BIN + " compare " + path("a.png") +
                  " " + path("claims.png") + mode + (*mode ? path("out.png") : std::string()));
    EXPECT_EQ(m.rc, 2) << mode << m.err;
    EXPECT_NE(m.err.find("claims.png"), std::string::npos) << m.err;
    EXPECT_LT(m.max_rss_mb, 100) << mode;
    EXPECT_LT(m.seconds, 5) << mode;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "out.png"));
  }
}

// A zlib bomb: 6.5 MB that really inflates to 16384x16384 RGBA (1 GiB). Decoding it whole
// with a diff image would take over 3 GiB; the memory budget refuses it before decoding.
TEST_F(CliCompare, MemoryBudgetRefusesBeforeAllocating) {
  const std::uint64_t raw = std::uint64_t{16384} * (1 + 16384 * 4);
  test::write_bytes(dir_ / "bomb.png", test::png_with_idat(16384, 16384, 8, 6, zeros_stream(raw)));
  const Measured m = run_measured(dir_, std::string(kAddressLimit) + "exec " + AOSUITE_BIN +
                                            " compare " + path("a.png") + " " + path("bomb.png") +
                                            " --mode antialiasing --diff " + path("out.png"));
  EXPECT_EQ(m.rc, 2) << m.err;
  EXPECT_NE(m.err.find(path("bomb.png") + ": 16384x16384 pixels"), std::string::npos) << m.err;
  EXPECT_NE(m.err.find("over the 1024 MiB memory budget"), std::string::npos) << m.err;
  EXPECT_EQ(std::count(m.err.begin(), m.err.end(), '\n'), 1) << m.err;
  EXPECT_LT(m.max_rss_mb, 100);
  EXPECT_LT(m.seconds, 5);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "out.png"));
  // Small images fit a small budget; byte-identical files need no whole image.
  const Outcome small = run(
      dir_, path("a.png") + " " + path("b.png") + " --memory-limit 1 --diff " + path("out.png"));
  EXPECT_EQ(small.rc, 1) << small.err;  // 20x30 pixels fit in 1 MiB
  const Measured whole = run_measured(dir_, std::string("exec ") + AOSUITE_BIN + " compare " +
                                                path("bomb.png") + " " + path("bomb.png"));
  EXPECT_EQ(whole.rc, 0) << whole.err;  // identical files: checked a band at a time
  EXPECT_LT(whole.max_rss_mb, 100);
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

// Every option says what it takes (FILE, DIR, MODE, ...), never CLI11's bare TEXT, and no
// default is one the docs do not name; check says what it does for every kind of case.
TEST(CliHelp, OptionsNameWhatTheyTake) {
  for (const char* cmd : {"compare", "check", "bless", "report merge", "tolerances suggest"}) {
    const test::Outcome r = test::run_shell(std::string(AOSUITE_BIN) + " " + cmd + " --help",
                                            std::filesystem::temp_directory_path());
    EXPECT_EQ(r.rc, 0) << cmd;
    EXPECT_EQ(r.out.find(" TEXT"), std::string::npos) << cmd << "\n" << r.out;
    EXPECT_EQ(r.out.find("=default"), std::string::npos) << cmd << "\n" << r.out;
  }
  const test::Outcome check = test::run_shell(std::string(AOSUITE_BIN) + " check --help",
                                              std::filesystem::temp_directory_path());
  EXPECT_EQ(check.out.find("Render a suite"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("-j,--jobs N"), std::string::npos) << check.out;
}

}  // namespace
}  // namespace aosuite

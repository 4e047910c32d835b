// The harness's parts without OpenGL: suite files, golden lookup, verdicts, shards, results.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>

#include "compare/opencv.hpp"
#include "harness/escape.hpp"
#include "harness/goldens.hpp"
#include "harness/html_report.hpp"
#include "harness/judge.hpp"
#include "harness/pass_record.hpp"
#include "harness/report_images.hpp"
#include "harness/results.hpp"
#include "harness/runner.hpp"
#include "harness/suite_file.hpp"
#include "png_fixture.hpp"
#include "suite_file_fixture.hpp"

namespace aosuite::harness {
namespace {

namespace fs = std::filesystem;

using SuiteFile = test::SuiteFile;

// The default goldens folder does not follow the suite file out of the project: like reports/,
// it is goldens/<name> in the working directory; only the suite's own key is relative to it.
TEST_F(SuiteFile, GoldensLieBesideTheSuiteUnlessItSaysWhere) {
  const fs::path elsewhere = dir_ / "outside" / "deep" / "s.toml";
  fs::create_directories(elsewhere.parent_path());
  const std::string image_case = "[[case]]\nname = \"a\"\nfiles = [\"a.png\"]\n";
  std::ofstream(elsewhere) << image_case;
  EXPECT_EQ(load_suite(elsewhere).goldens,
            (dir_ / "outside" / "deep" / "goldens" / "s").lexically_normal());
  std::ofstream(elsewhere) << "goldens = \"../g\"\n" << image_case;
  EXPECT_EQ(load_suite(elsewhere).goldens, (dir_ / "outside" / "g").lexically_normal());
}

// A suite's name names its report and goldens folders: nothing that leaves them.
TEST_F(SuiteFile, NamesThatWouldLeaveTheirFoldersAreRejected) {
  for (const char* name : {"..", ".", ".hidden", "a/b", "a\\u0001b", ""}) {
    const std::string msg = error_of(std::string("name = \"") + name +
                                     "\"\n[[case]]\nname = \"a\"\nfiles = [\"a.png\"]\n");
    EXPECT_NE(msg.find(":1:"), std::string::npos) << name << " -> " << msg;
    EXPECT_NE(msg.find("suite name"), std::string::npos) << name << " -> " << msg;
    EXPECT_EQ(msg.find('\x01'), std::string::npos) << msg;  // shown escaped
  }
  EXPECT_TRUE(valid_name("default"));
  EXPECT_TRUE(valid_name("corner-front-sao-48x27-r1.5"));
  for (const char* bad : {"..", ".", ".x", "../evil", "a/b", "a~b", "a b", ""}) {
    EXPECT_FALSE(valid_name(bad)) << bad;
  }
  // Too long is said as that, not as a character it does not hold.
  EXPECT_TRUE(valid_name(std::string(kMaxNameLength, 'a')));
  EXPECT_EQ(name_problem(std::string(230, 'a')),
            "is 230 characters long, over the 200 a name may have (it names a folder)");
  std::ofstream(dir_ / "long.toml")
      << "[[case]]\nname = \"" << std::string(230, 'c') << "\"\nfiles = [\"x.png\"]\n";
  try {
    load_suite(dir_ / "long.toml");
    ADD_FAILURE() << "an over-long case id was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("case id 'cccc"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("...' is 230 characters long"), std::string::npos)
        << e.what();
  }
}

TEST_F(SuiteFile, ImageCasesNameTheirImagesAndKeepTypedParams) {
  fs::create_directories(dir_ / "suites" / "shots");
  std::ofstream(dir_ / "suites" / "draw.py") << "";
  const Suite s = load_suite(write(R"(
[defaults]
width = 64
height = 48
params = { quality = 3 }
[[case]]
name = "chart"
command = ["python3", "{suite_dir}/draw.py", "--out", "{out}", "--w", "{width}", "{quality}{{x}}"]
outputs = ["chart.png", "sub/legend.png"]
inputs = ["draw.py"]
timeout = 5
params = { gamma = 2.2, label = "a b", on = true, list = [1, 2] }
[[case]]
name = "photo"
files = ["shots/photo.png"]
)"));
  ASSERT_EQ(s.cases.size(), 2u);
  const Case& c = s.cases[0];
  ASSERT_TRUE(c.source);
  EXPECT_EQ(c.id, "chart");
  EXPECT_EQ(c.images, (std::vector<std::string>{"chart", "legend"}));
  EXPECT_EQ(c.source->outputs[1], "sub/legend.png");
  EXPECT_EQ(c.source->timeout_seconds, 5);
  EXPECT_EQ(c.values["quality"], 3);
  EXPECT_EQ(c.values["gamma"], 2.2);
  EXPECT_EQ(c.values["on"], true);
  EXPECT_EQ(c.values["list"], nlohmann::json::array({1, 2}));
  std::map<std::string, std::string> v = command_placeholders(c);
  v["out"] = "/o";
  EXPECT_EQ(expand_placeholders(c.source->command[6], v, false), "3{x}");
  EXPECT_EQ(expand_placeholders("{label}", v, true), "'a b'");
  EXPECT_EQ(expand_placeholders("{width}x{height}", v, false), "64x48");
  EXPECT_EQ(s.cases[1].width, 64);
  EXPECT_THROW(expand_placeholders("{nope}", v, false), std::invalid_argument);
  EXPECT_THROW(expand_placeholders("{out", v, false), std::invalid_argument);
  EXPECT_EQ(s.cases[1].images, (std::vector<std::string>{"photo"}));
  EXPECT_EQ(s.cases[1].source->files[0], dir_ / "suites" / "shots/photo.png");
}

TEST_F(SuiteFile, MalformedImageCasesNameFileLineAndReason) {
  const std::string head = "[[case]]\nname = \"x\"\n";
  EXPECT_NE(
      error_of("[[case]]\nfiles = [\"a.png\"]\n").find("s.toml:1:1: an image case needs name"),
      std::string::npos);
  EXPECT_NE(error_of(head + "command = [\"true\"]\n").find("a command case needs outputs"),
            std::string::npos);
  EXPECT_NE(error_of(head + "files = [\"a.png\"]\ncommand = [\"true\"]\n").find("command or files"),
            std::string::npos);
  EXPECT_NE(
      error_of(head + "files = [\"a.svg\"]\n").find("s.toml:3:9: 'a.svg' is not an image file"),
      std::string::npos);
  EXPECT_NE(error_of(head + "files = [\"a/x.png\", \"b/x.png\"]\n").find("two images named 'x'"),
            std::string::npos);
  EXPECT_NE(error_of(head + "files = [\"golden_x.png\"]\n").find("golden_"), std::string::npos);
  // Two types of one stem are named apart by type: diff.png would become diff_png, which the
  // report's diff of an image 'png' would be.
  EXPECT_NE(
      error_of(head + "files = [\"diff.png\", \"diff.exr\"]\n").find("would be named 'diff_png'"),
      std::string::npos);
  EXPECT_NE(error_of(head + "command = [\"true\"]\noutputs = [\"../x.png\"]\n")
                .find("must be a relative path inside"),
            std::string::npos);
  EXPECT_NE(error_of(head + "command = [\"true\"]\noutputs = [\"x.png\"]\ninputs = [\"no.txt\"]\n")
                .find("s.toml:5:10: no input file"),
            std::string::npos);
  EXPECT_NE(
      error_of(head + "files = [\"x.png\"]\nscene = \"corner\"\n").find("unknown key 'scene'"),
      std::string::npos);
  // Without a registered kind, a case that is neither files nor a command names what it needs.
  EXPECT_NE(error_of("[[case]]\nscene = \"corner\"\n").find("s.toml:1:1: a case needs command"),
            std::string::npos);
  // Width and height are what the command is told: both or neither, never half a default.
  EXPECT_NE(error_of(head + "files = [\"x.png\"]\nwidth = 64\n")
                .find("s.toml:1:1: an image case "
                      "gives width and height "
                      "together"),
            std::string::npos);
  EXPECT_NE(error_of(head + "command = [\"a\", \"{width}\"]\noutputs = [\"x.png\"]\n")
                .find("unknown placeholder '{width}'"),
            std::string::npos);
  EXPECT_NE(error_of(head + "files = [\"x.png\"]\ntimeout = 3\n").find("belongs to a command case"),
            std::string::npos);
  EXPECT_NE(error_of(head + "command = [\"a\", \"{oops}\"]\noutputs = [\"x.png\"]\n")
                .find("s.toml:3:11: unknown placeholder '{oops}'"),
            std::string::npos);
}

// The first pass whose hash differs, and the ones before it that match; nothing to say when the
// golden has no record or the two renders ran different passes (another blur setting).
TEST(PassRecord, NamesTheFirstPassThatDiffers) {
  const PassHashes golden = {{"gbuffer", "1"}, {"ao", "2"}, {"blur", "3"}, {"blend", "4"}};
  PassHashes now = golden;
  EXPECT_EQ(first_differing_pass(golden, now), "every pass identical");
  now[3].second = "x";
  EXPECT_EQ(first_differing_pass(golden, now), "blend differs (gbuffer, ao, blur identical)");
  now[1].second = "x";
  EXPECT_EQ(first_differing_pass(golden, now), "ao differs (gbuffer identical)");
  now[0].second = "x";
  EXPECT_EQ(first_differing_pass(golden, now), "gbuffer differs");
  EXPECT_EQ(first_differing_pass({}, now), "");
  EXPECT_EQ(first_differing_pass({{"gbuffer", "1"}, {"ao", "2"}, {"blend", "4"}}, now), "");

  test::TempDir dir;
  const fs::path png = dir / "with_ao.png";
  EXPECT_EQ(pass_record(png), dir / "with_ao.passes.json");
  EXPECT_TRUE(read_pass_record(png).empty());  // an older golden: no record
  const std::vector<unsigned char> bytes = pass_record_bytes(golden);
  std::ofstream(pass_record(png), std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  EXPECT_EQ(read_pass_record(png), golden);
  std::ofstream(pass_record(png)) << "{not json";
  EXPECT_TRUE(read_pass_record(png).empty());
}

TEST(FolderSuite, PairsPngFilesByRelativePath) {
  const test::TempDir dir;
  fs::create_directories(dir.path() / "a" / "sub");
  fs::create_directories(dir.path() / "e" / "sub");
  for (const char* f : {"a/same.png", "a/sub/x y.png", "a/new.png", "e/same.png", "e/sub/x y.png",
                        "e/gone.png", "a/notes.txt", "a/.hidden.png"}) {
    std::ofstream(dir.path() / f) << "x";
  }
  const Suite s = folder_suite(dir.path() / "a", dir.path() / "e", {});
  std::map<std::string, std::pair<std::string, bool>> got;
  for (const Case& c : s.cases) got[c.id] = {c.source->path, c.source->deleted};
  EXPECT_EQ(got.size(), 4u);
  EXPECT_EQ(got.at("same.png"), std::make_pair(std::string("same.png"), false));
  EXPECT_EQ(got.at("sub__x_y.png"), std::make_pair(std::string("sub/x y.png"), false));
  EXPECT_EQ(got.at("new.png").second, false);
  EXPECT_EQ(got.at("gone.png").second, true);
  EXPECT_NE(s.bless_prefix.find("aosuite bless --actual "), std::string::npos);
  EXPECT_THROW(folder_suite(dir.path() / "missing", dir.path() / "e", {}), std::runtime_error);
  std::ofstream(dir.path() / "a" / "sub__x_y.png") << "x";  // collides with sub/x y.png
  EXPECT_THROW(folder_suite(dir.path() / "a", dir.path() / "e", {}), std::runtime_error);
}

TEST(Goldens, PlatformKeyIsTheRendererFieldSanitised) {
  EXPECT_EQ(
      platform_key("Mesa | llvmpipe (LLVM 15.0.6, 256 bits) | 4.5 (Core Profile) Mesa 22.3.6"),
      "llvmpipe-llvm-15-0-6-256-bits");
  EXPECT_EQ(platform_key("NVIDIA Corporation | NVIDIA H100 80GB HBM3/PCIe/SSE2 | 4.6.0"),
            "nvidia-h100-80gb-hbm3-pcie-sse2");
  // The run's backend and device follow the driver's fields; EGL and OSMesa share goldens.
  EXPECT_EQ(platform_key("Mesa/X.org | llvmpipe (LLVM 15.0.6, 256 bits) | 4.5 (Core Profile) "
                         "Mesa 22.3.6 | EGL device 0 (software)"),
            platform_key("Mesa/X.org | llvmpipe (LLVM 15.0.6, 256 bits) | 4.5 (Core Profile) "
                         "Mesa 22.3.6 | OSMesa"));
  EXPECT_EQ(platform_key(""), "unknown");
}

TEST(Goldens, PlatformGoldensReplaceGenericOnesAndVariantsFollowThePrimary) {
  test::TempDir dir;
  const fs::path c = dir.path();
  for (const fs::path& p :
       {c / "with_ao.png", c / "with_ao~b.png", c / "with_ao~a.png", c / "ao_only.png",
        c / ".with_ao.png.tmp-123456", c / "llvm" / "ao_only.png"}) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << "x";
  }
  EXPECT_EQ(accepted_goldens(c, "with_ao", ".png", "llvm"),
            (std::vector<fs::path>{c / "with_ao.png", c / "with_ao~a.png", c / "with_ao~b.png"}));
  EXPECT_EQ(accepted_goldens(c, "ao_only", ".png", "llvm"),
            std::vector<fs::path>{c / "llvm" / "ao_only.png"});
  EXPECT_EQ(accepted_goldens(c, "ao_only", ".png", "other"),
            std::vector<fs::path>{c / "ao_only.png"});
  EXPECT_TRUE(accepted_goldens(c, "no_ao", ".png", "").empty());
  EXPECT_EQ(golden_path(c, "with_ao", ".png", "", ""), c / "with_ao.png");
  EXPECT_EQ(golden_path(c, "with_ao", ".png", "llvm", "x"), c / "llvm" / "with_ao~x.png");
}

// `bless --platform` replaces the generic golden on that platform, not the variants accepted
// beside it.
TEST(Goldens, APlatformGoldenKeepsTheGenericVariantsAccepted) {
  test::TempDir dir;
  const fs::path c = dir.path();
  for (const fs::path& p : {c / "with_ao.png", c / "with_ao~old-driver.png",
                            c / "llvm" / "with_ao.png", c / "llvm" / "with_ao~x.png"}) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << "x";
  }
  EXPECT_EQ(accepted_goldens(c, "with_ao", ".png", "llvm"),
            (std::vector<fs::path>{c / "llvm" / "with_ao.png", c / "llvm" / "with_ao~x.png",
                                   c / "with_ao~old-driver.png"}));
  EXPECT_EQ(accepted_goldens(c, "with_ao", ".png", "other"),
            (std::vector<fs::path>{c / "with_ao.png", c / "with_ao~old-driver.png"}));
}

// A golden folder that exists but cannot be listed is an error to fix, not "no golden yet".
TEST(Goldens, AnUnreadableGoldenFolderIsAnErrorNotMissing) {
  test::TempDir dir;
  EXPECT_TRUE(accepted_goldens(dir.path() / "absent", "with_ao", ".png", "llvm").empty());
  std::ofstream(dir.path() / "case") << "a file where the folder should be";
  try {
    accepted_goldens(dir.path() / "case", "with_ao", ".png", "");
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("case: cannot read the golden folder"), std::string::npos)
        << e.what();
  }
  fs::create_directories(dir.path() / "c2");
  std::ofstream(dir.path() / "c2" / "llvm") << "a file where the platform folder should be";
  EXPECT_THROW(accepted_goldens(dir.path() / "c2", "with_ao", ".png", "llvm"), std::runtime_error);
  if (::geteuid() != 0) {  // root reads any folder
    fs::create_directories(dir.path() / "locked");
    fs::permissions(dir.path() / "locked", fs::perms::none);
    EXPECT_THROW(accepted_goldens(dir.path() / "locked", "with_ao", ".png", ""),
                 std::runtime_error);
    fs::permissions(dir.path() / "locked", fs::perms::owner_all);
  }
}

// A case's goldens are replaced all or nothing: a failure on the second file leaves the first
// as it was, and no temporary behind.
TEST(Goldens, ReplacingACaseIsAllOrNothing) {
  test::TempDir dir;
  const fs::path c = dir.path() / "case";
  fs::create_directories(c / "ao_only.png");  // cannot be replaced by a file
  std::ofstream(c / "with_ao.png") << "old";
  const std::vector<unsigned char> bytes{'n', 'e', 'w'};
  try {
    replace_goldens({{c / "with_ao.png", bytes}, {c / "ao_only.png", bytes}});
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("ao_only.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nothing was replaced"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_file(c / "with_ao.png"), (std::vector<unsigned char>{'o', 'l', 'd'}));
  fs::remove(c / "ao_only.png");
  replace_goldens({{c / "with_ao.png", bytes}, {c / "llvm" / "ao_only.png", bytes}});
  EXPECT_EQ(read_file(c / "with_ao.png"), bytes);
  EXPECT_EQ(read_file(c / "llvm" / "ao_only.png"), bytes);
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::recursive_directory_iterator(c)) ++files;
  EXPECT_EQ(files, 3);  // with_ao.png, llvm/, llvm/ao_only.png: no temporaries
}

// What a killed bless leaves is removed by the next one; a live bless's temporaries are not.
TEST(Goldens, StaleTemporariesAreRemoved) {
  test::TempDir dir;
  const fs::path c = dir.path();
  const fs::path old_form = c / ".with_ao.png.tmp-AbC123";
  const fs::path dead = c / "llvm" / ".with_ao.png.bless-999999999-AbC123";
  const fs::path live = c / fmt::format(".with_ao.png.bless-{}-AbC123", ::getpid());
  const fs::path young = c / ".ao_only.png.tmp-XyZ789";
  for (const fs::path& p : {old_form, dead, live, young, c / "with_ao.png"}) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << "x";
  }
  fs::last_write_time(old_form, fs::file_time_type::clock::now() - std::chrono::hours(1));
  EXPECT_EQ(remove_stale_temporaries(c), 2);
  EXPECT_FALSE(fs::exists(old_form));
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(young));  // perhaps an older bless still writing
  EXPECT_TRUE(fs::exists(c / "with_ao.png"));
}

class Judge : public ::testing::Test {
 protected:
  Judge() : render_(40, 30, CV_8UC4, cv::Scalar(100, 100, 100, 255)) {
    png_ = encode_png_rgba8(render_, 6);
  }
  fs::path golden(const std::string& name, const cv::Mat& m) {
    write_png_rgba8(dir_ / name, m);
    return dir_ / name;
  }
  ImageVerdict run(const std::vector<fs::path>& goldens, const Tolerance& t = {}) {
    return judge("with_ao", png_, read_goldens(goldens), t, true);
  }
  test::TempDir dir_;
  cv::Mat render_;
  std::vector<unsigned char> png_;
};

// A golden is read once per judgement: the verdict is on the bytes read (those the judge hash
// covers), whatever a bless writes to the file afterwards.
TEST_F(Judge, TheGoldenBytesReadOnceAreTheBytesJudged) {
  const fs::path g = golden("g.png", render_);
  const std::vector<ReadGolden> read = read_goldens({g});
  write_png_rgba8(g, cv::Mat(30, 40, CV_8UC4, cv::Scalar(0, 0, 255, 255)));  // a bless since
  EXPECT_EQ(judge("with_ao", png_, read, {}, true).status, Status::kPass);
  EXPECT_EQ(judge("with_ao", png_, read_goldens({g}), {}, true).status, Status::kFail);
  const std::vector<ReadGolden> none = read_goldens({dir_ / "missing.png"});
  ASSERT_EQ(none.size(), 1u);
  EXPECT_TRUE(none[0].bytes.empty());
  const ImageVerdict v = judge("with_ao", png_, none, {}, true);
  EXPECT_EQ(v.status, Status::kError);
  EXPECT_NE(v.message.find("missing.png"), std::string::npos) << v.message;
}

TEST_F(Judge, IdenticalBytesPassWithoutComparing) {
  write_file_atomic(dir_ / "g.png", png_);
  const ImageVerdict v = run({dir_ / "g.png"});
  EXPECT_EQ(v.status, Status::kPass);
  EXPECT_TRUE(v.identical);
}

TEST_F(Judge, MissingGoldenIsNewNotPass) { EXPECT_EQ(run({}).status, Status::kNew); }

TEST_F(Judge, UnreadableGoldenIsAnErrorNamingIt) {
  std::ofstream(dir_ / "bad.png") << "not a png";
  const ImageVerdict v = run({dir_ / "bad.png"});
  EXPECT_EQ(v.status, Status::kError);
  EXPECT_NE(v.message.find("bad.png"), std::string::npos) << v.message;
}

TEST_F(Judge, GoldenOfAnotherSizeFailsNamingBothSizes) {
  const ImageVerdict v =
      run({golden("g.png", cv::Mat(30, 40, CV_8UC4, cv::Scalar(100, 100, 100, 255)))});
  EXPECT_EQ(v.status, Status::kFail);
  EXPECT_NE(v.message.find("expected is 40x30, actual is 30x40"), std::string::npos) << v.message;
}

TEST_F(Judge, MismatchIsMeasuredAgainstTheAllowedPercentage) {
  cv::Mat g = render_.clone();
  g(cv::Rect(0, 0, 4, 3)).setTo(cv::Scalar(200, 0, 0, 255));  // 12 of 1200 pixels: 1 %
  const fs::path file = golden("g.png", g);
  Tolerance t;
  EXPECT_EQ(run({file}, t).max_channel_delta, 100);  // over the default budget of 8 too
  // Every limit but the percentage lifted by name (12 pixels moved by 200 shift the mean too).
  t.max_mismatch_percent = 0.99, t.max_channel_delta = 255;
  t.max_mean_shift = t.max_mean_delta = 255;
  ImageVerdict v = run({file}, t);
  EXPECT_EQ(v.status, Status::kFail);
  EXPECT_EQ(v.mismatch_text, "1.00");
  EXPECT_EQ(cv::Size(v.diff.width(), v.diff.height()), render_.size());  // for the report
  t.max_mismatch_percent = 1;
  EXPECT_EQ(run({file}, t).status, Status::kPass);
  t.max_channel_delta = 99;  // the red channel moved by 100
  v = run({file}, t);
  EXPECT_EQ(v.status, Status::kFail);
  EXPECT_EQ(v.max_channel_delta, 100);
}

TEST_F(Judge, IgnoredBoxesAreNotJudged) {
  cv::Mat g = render_.clone();
  g(cv::Rect(10, 5, 3, 2)).setTo(cv::Scalar(0, 0, 0, 255));
  const fs::path file = golden("g.png", g);
  Tolerance t;
  t.ignore = {{10, 5, 12, 6}};  // inclusive, as Resemble's boxes
  EXPECT_EQ(run({file}, t).status, Status::kPass);
  t.ignore = {{10, 5, 11, 6}};
  EXPECT_EQ(run({file}, t).status, Status::kFail);
}

// README: "pixels where the mask is non-zero are ignored": paint what to hide white.
TEST_F(Judge, MaskNonZeroPixelsAreIgnoredAndBlackOnesJudged) {
  cv::Mat g = render_.clone();
  g(cv::Rect(10, 5, 3, 2)).setTo(cv::Scalar(0, 0, 0, 255));
  const fs::path file = golden("g.png", g);
  Tolerance t;
  cv::Mat mask(render_.size(), CV_8UC4, cv::Scalar(0, 0, 0, 255));
  mask(cv::Rect(10, 5, 3, 2)).setTo(cv::Scalar(255, 255, 255, 255));
  t.mask = golden("hide_changed.png", mask);
  EXPECT_EQ(run({file}, t).status, Status::kPass);
  mask(cv::Rect(10, 5, 3, 2)).setTo(cv::Scalar(0, 1, 0, 255));  // any non-zero channel
  t.mask = golden("hide_changed_dim.png", mask);
  EXPECT_EQ(run({file}, t).status, Status::kPass);
  // The opposite mask hides everything but the change: the change is judged and fails.
  cv::Mat inverse(render_.size(), CV_8UC4, cv::Scalar(255, 255, 255, 255));
  inverse(cv::Rect(10, 5, 3, 2)).setTo(cv::Scalar(0, 0, 0, 255));
  t.mask = golden("hide_rest.png", inverse);
  EXPECT_EQ(run({file}, t).status, Status::kFail);
}

// An identical image that a two-sided budget fails reads the mask first for its diff: a mask of
// another size is an error naming it, not an exception out of judge().
TEST_F(Judge, AMaskOfAnotherSizeIsAnErrorEvenBesideAnIdenticalGolden) {
  write_file_atomic(dir_ / "g.png", png_);
  Tolerance t;
  t.min_differing_pixels = 1;  // a change is expected, and none came
  t.mask = golden("small_mask.png", cv::Mat(3, 3, CV_8UC4, cv::Scalar(0, 0, 0, 255)));
  const ImageVerdict v = run({dir_ / "g.png"}, t);
  EXPECT_EQ(v.status, Status::kError);
  EXPECT_NE(v.message.find("small_mask.png is 3x3"), std::string::npos) << v.message;
}

TEST_F(Judge, AnyAcceptedVariantPasses) {
  const fs::path far = golden("g.png", cv::Mat(render_.size(), CV_8UC4, cv::Scalar(0, 0, 0, 255)));
  cv::Mat near = render_.clone();
  near.at<cv::Vec4b>(0, 0) = {101, 100, 100, 255};
  const fs::path close = golden("g~linux.png", near);
  const ImageVerdict v = run({far, close});
  EXPECT_EQ(v.status, Status::kPass);
  EXPECT_EQ(v.golden, close);
  EXPECT_EQ(run({far}).status, Status::kFail);
}

// A truncated golden is damage to repair: ERROR, whether it is the primary or a variant and
// whether or not another variant passes or fails.
TEST_F(Judge, ATruncatedGoldenBesideAValidVariantIsAnError) {
  const fs::path good = golden("g~ok.png", render_);
  cv::Mat other = render_.clone();
  other.setTo(cv::Scalar(0, 0, 0, 255));
  const fs::path far = golden("g~far.png", other);
  const std::vector<unsigned char> whole = encode_png_rgba8(render_, 0);
  write_file_atomic(dir_ / "g.png", std::span<const unsigned char>(whole).first(whole.size() / 2));
  for (const auto& goldens : std::vector<std::vector<fs::path>>{{dir_ / "g.png", good},
                                                                {good, dir_ / "g.png"},
                                                                {dir_ / "g.png", far},
                                                                {far, dir_ / "g.png"}}) {
    const ImageVerdict v = run(goldens);
    EXPECT_EQ(v.status, Status::kError) << goldens[0] << " " << goldens[1];
    EXPECT_EQ(v.golden, dir_ / "g.png");
    EXPECT_NE(v.message.find("g.png"), std::string::npos) << v.message;
  }
  EXPECT_EQ(run({good}).status, Status::kPass);
}

TEST(Shards, PartitionTheFilteredCasesAndHonourGoogleTestVariables) {
  Suite s;
  for (const std::string id : {"c0", "c1", "c2", "c3", "c4", "c5", "c6", "other"}) {
    s.cases.emplace_back().id = id;
  }
  std::vector<std::string> seen;
  for (int i = 0; i < 3; ++i) {
    Selection sel{.filter = "^c"};
    set_shard(sel, std::to_string(i) + "/3");
    for (const Case* c : select(s, sel)) seen.push_back(c->id);
  }
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(seen, (std::vector<std::string>{"c0", "c1", "c2", "c3", "c4", "c5", "c6"}));
  Selection env;
  setenv("GTEST_SHARD_INDEX", "1", 1);
  setenv("GTEST_TOTAL_SHARDS", "4", 1);
  set_shard(env, "");
  unsetenv("GTEST_SHARD_INDEX");
  unsetenv("GTEST_TOTAL_SHARDS");
  EXPECT_EQ(env.shard_index, 1);
  EXPECT_EQ(env.shard_count, 4);
  for (const char* bad : {"3/3", "1", "a/2", "-1/2", "1/0", "1/2x"}) {
    Selection sel;
    EXPECT_THROW(set_shard(sel, bad), std::invalid_argument) << bad;
  }
  Selection sel{.filter = "("};
  EXPECT_THROW(select(s, sel), std::invalid_argument);
}

// --filter searches ids; the filter printed to bless failing cases matches exactly them.
TEST(Shards, TheExactFilterMatchesWholeIdsOnly) {
  Suite s;
  for (const std::string id : {"corner-front-alchemy-48x27", "x-corner-front-alchemy-48x27",
                               "corner-front-alchemy-48x27-r1.5", "corner-front-alchemy-48x27-r1x5",
                               "plane-above-sao-8x8"}) {
    s.cases.emplace_back().id = id;
  }
  auto ids = [&](const std::string& filter) {
    std::vector<std::string> out;
    for (const Case* c : select(s, Selection{.filter = filter})) out.push_back(c->id);
    return out;
  };
  EXPECT_EQ(ids("front-alchemy").size(), 4u);  // searched: documented, and what ctest -R does
  EXPECT_EQ(ids(exact_filter({"corner-front-alchemy-48x27"})),
            std::vector<std::string>{"corner-front-alchemy-48x27"});
  EXPECT_EQ(ids(exact_filter({"corner-front-alchemy-48x27-r1.5", "plane-above-sao-8x8"})),
            (std::vector<std::string>{"corner-front-alchemy-48x27-r1.5", "plane-above-sao-8x8"}));
  s.file = "my suites/it's.toml";
  s.goldens = "g", s.goldens_given = true;
  EXPECT_EQ(bless_command(bless_prefix(s), {"a-b", "c.d"}),
            R"(aosuite bless 'my suites/it'\''s.toml' --goldens g --filter '^(a-b|c\.d)$')");
}

TEST(Results, RoundTripThroughJson) {
  CaseResult c;
  c.id = "a-b-sao-8x8", c.width = c.height = 8;
  c.labels = {{"scene", "a"}, {"view", "b"}, {"technique", "sao"}};
  c.figures = {{"ao_effect_less", 12.5}};
  c.params = {{"radius", 10}, {"blur", "none"}, {"weights", nlohmann::json::array({1, 0.5})}};
  c.kind = "command", c.source = "draw {out}", c.exit_status = 3, c.attempts = 2;
  c.command_stderr = "line 1\nline 2\n";
  c.tolerance.mode = resemble::Mode::kAntialiasing, c.tolerance.ignore = {{1, 2, 3, 4}};
  c.status = Status::kFail, c.message = "with_ao: mismatch";
  ImageVerdict v;
  v.image = "with_ao", v.status = Status::kFail, v.mismatch_percent = 1.25,
  v.mismatch_text = "1.25";
  v.golden = "g/with_ao.png";
  c.images = {v};
  c.files = {{"with_ao", "a-b-sao-8x8/with_ao.png"}};
  c.times = {{"ao", 1.5}};
  c.input_hash = "12", c.judge_hash = "34";
  RunResults r;
  r.suite = "s", r.environment = "gl", r.platform = "p", r.cases = {c};
  r.bless_prefix = "aosuite bless suites/s.toml";
  const RunResults back = run_from_json(to_json(r));
  EXPECT_EQ(to_json(back), to_json(r));
  EXPECT_EQ(back.cases[0].tolerance.mode, resemble::Mode::kAntialiasing);
  EXPECT_EQ(back.cases[0].params.at("radius"), 10);  // a number, not "10"
  EXPECT_EQ(back.cases[0].command_stderr, "line 1\nline 2\n");
  EXPECT_EQ(exit_code(count(back)), 1);
  r.cases[0].status = Status::kFlaky;
  const RunResults flaky = run_from_json(to_json(r));
  EXPECT_EQ(flaky.cases[0].status, Status::kFlaky);
  EXPECT_EQ(count(flaky).flaky, 1);
  EXPECT_EQ(exit_code(count(flaky)), 0);  // flaky cases passed in the end
}

// A float image as the report's preview draws it: linear light clamped to [0, 1] and
// sRGB-encoded (NaN black), sRGB-encoded floats (16-bit) clamped only, one channel as grey.
TEST(ReportImages, FloatPicturesAreClampedAndSrgbEncodedForTheScreen) {
  Picture p;
  p.is_float = true;
  p.floats = {.width = 3,
              .height = 1,
              .channels = 3,
              .data = {0.5f, 0.0f, 1.5f, -1.0f, std::nanf(""), 0.002f, 1.0f, 0.2f, 0.0f}};
  const auto px = [](const RgbaImage& img, int x) {
    const unsigned char* q = img.data() + 4 * x;
    return std::vector<int>{q[0], q[1], q[2], q[3]};
  };
  const RgbaImage shown = display_rgba8(p);
  ASSERT_EQ(shown.width(), 3);
  EXPECT_EQ(px(shown, 0), (std::vector<int>{188, 0, 255, 255}));  // 0.7354 of 255
  EXPECT_EQ(px(shown, 1), (std::vector<int>{0, 0, 7, 255}));      // 0.002 * 12.92 of 255
  EXPECT_EQ(px(shown, 2), (std::vector<int>{255, 124, 0, 255}));
  p.floats.srgb = true;
  EXPECT_EQ(px(display_rgba8(p), 0), (std::vector<int>{128, 0, 255, 255}));
  p.floats = {.width = 1, .height = 1, .channels = 1, .data = {0.2f}};
  EXPECT_EQ(px(display_rgba8(p), 0), (std::vector<int>{124, 124, 124, 255}));
}

// A linear float preview is darkened by the whole stops that keep its highlights (the 99.9th
// percentile) from clipping, and its name says how many.
TEST(ReportImages, BrightFloatPreviewsAreDarkenedByWholeStops) {
  Picture p;
  p.is_float = true;
  const auto stops = [&](std::vector<float> data) {
    p.floats = {.width = int(data.size()), .height = 1, .channels = 1, .data = std::move(data)};
    return preview_stops(p);
  };
  EXPECT_EQ(stops({0.0f, 0.5f, 1.0f}), 0);
  EXPECT_EQ(stops({1.5f}), 1);
  EXPECT_EQ(stops({4.0f, 0.0f}), 2);
  EXPECT_EQ(stops({4.01f}), 3);
  EXPECT_EQ(stops({0.2f, std::numeric_limits<float>::infinity(), std::nanf("")}), 0);
  EXPECT_EQ(stops({1e30f}), 24);
  std::vector<float> fireflies(9999, 0.5f);  // two bright pixels in 10,001 do not darken it
  fireflies.insert(fireflies.end(), {1e4f, 1e4f});
  EXPECT_EQ(stops(fireflies), 0);
  p.floats.srgb = true;
  EXPECT_EQ(preview_stops(p), 0);  // 16-bit: sRGB-encoded, never above 1
  p.floats = {.width = 1, .height = 1, .channels = 1, .data = {1.5f}};
  EXPECT_EQ(display_rgba8(p, 1).data()[0], 225);  // 1.5 / 2 = 0.75: sRGB 0.8808
  EXPECT_EQ(stops_of_preview("x/ao.exr.0123456789abcdef.s3.png"), 3);
  EXPECT_EQ(stops_of_preview("x/ao.exr.0123456789abcdef.s0.png"), 0);
  for (const char* odd : {"a.s03.png", "a.s25.png", "a.sx.png", "a.s.png", "a.s3.exr"})
    EXPECT_EQ(stops_of_preview(odd), 0) << odd;
}

TEST(Escape, MarkupCharactersAreEscaped) {
  EXPECT_EQ(escape_markup(R"(<a href="x">'&'</a>)"),
            "&lt;a href=&quot;x&quot;&gt;&#39;&amp;&#39;&lt;/a&gt;");
}

// Bytes that are not UTF-8 and control characters become visible escapes: JSON, XML and a
// terminal stay well-formed; valid text (accents, CJK, emoji) is kept.
TEST(Escape, NonUtf8AndControlBytesAreEscaped) {
  EXPECT_EQ(printable("caf\xc3\xa9 \xe6\x97\xa5 \xf0\x9f\x98\x80"),
            "caf\xc3\xa9 \xe6\x97\xa5 \xf0\x9f\x98\x80");
  EXPECT_EQ(printable("a\xff"
                      "b"),
            "a\\xffb");
  EXPECT_EQ(printable("line\nfeed\ttab\x01\x7f"), "line\\x0afeed\\x09tab\\x01\\x7f");
  EXPECT_EQ(printable("\xc2\x85"), "\\u0085");              // C1 control
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");           // overlong '/'
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");  // a surrogate
  EXPECT_EQ(printable("\xe6\x97"), "\\xe6\\x97");           // cut short
  EXPECT_EQ(escape_markup("<\x01\xff>"), "&lt;\\x01\\xff&gt;");
  EXPECT_EQ(shell_quote("suites/t.toml"), "suites/t.toml");
  EXPECT_EQ(shell_quote("it's"), R"('it'\''s')");
  EXPECT_EQ(shell_quote("a\xff'b"), R"($'a\xff\'b')");
  EXPECT_EQ(shell_quote(""), "''");
}

// results.json of any path is valid JSON; a shard's results.json cannot point outside its
// folders.
TEST(Results, AnyBytesMakeValidJsonAndReadPathsStayInside) {
  CaseResult c;
  c.id = "a-b-sao-8x8";
  c.status = Status::kError, c.message = "dir\xff\x01/with_ao.png: cannot read";
  c.files = {{"with_ao", "a-b-sao-8x8/with_ao.png"}};
  RunResults r;
  r.suite = "s", r.suite_file = "suites\xfe/s.toml", r.cases = {c};
  const std::string text = to_json(r).dump();
  EXPECT_NE(text.find("dir\\\\xff\\\\x01/with_ao.png"), std::string::npos) << text;
  EXPECT_EQ(run_from_json(nlohmann::json::parse(text)).cases.size(), 1u);
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"id", "../../escape"},
                                                        {"id", ".."},
                                                        {"files", "../../../etc/hostname"},
                                                        {"files", "/etc/hostname"},
                                                        {"files", "a-b-sao-8x8/../../x.png"},
                                                        {"files", "other-case/with_ao.png"}}) {
    nlohmann::json j = to_json(c);
    if (key == "id") {
      j["id"] = value;
    } else {
      j["files"]["with_ao"] = value;
    }
    EXPECT_THROW(case_from_json(j), std::runtime_error) << key << " = " << value;
  }
}

// A shard's results.json is outside input: numbers that are not ints are refused rather than
// converted (a float beyond int's range is undefined behaviour), and so are ignore boxes of
// fewer than four numbers rather than read past their end (found by results_json_fuzz).
TEST(Results, NumbersThatAreNotIntsAndShortBoxesAreRefused) {
  CaseResult c;
  c.id = "a", c.width = c.height = 8;
  c.images = {ImageVerdict{}};
  const nlohmann::json good = to_json(c);
  ASSERT_NO_THROW(case_from_json(good));
  using Pointer = nlohmann::json::json_pointer;
  for (const auto& [where, value] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"/width", -5.5e118},
           {"/height", 3000000000u},
           {"/exit_status", -2147483649LL},
           {"/attempts", 1.5},
           {"/tolerance/max_channel_delta", 1e300},
           {"/images/0/max_channel_delta", "7"},
           {"/tolerance/ignore", nlohmann::json::array({nlohmann::json::array({1})})},
           {"/tolerance/ignore", nlohmann::json::array({1, 2, 3, 4})}}) {
    nlohmann::json j = good;
    j[Pointer(where)] = value;
    EXPECT_ANY_THROW(case_from_json(j)) << where << " = " << value.dump();
  }
}

}  // namespace
}  // namespace aosuite::harness

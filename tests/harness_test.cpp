// The harness's parts without OpenGL: suite files, golden lookup, verdicts, shards, results.
#include <gtest/gtest.h>

#include <fstream>

#include "compare/opencv.hpp"
#include "harness/escape.hpp"
#include "harness/goldens.hpp"
#include "harness/html_report.hpp"
#include "harness/judge.hpp"
#include "harness/results.hpp"
#include "harness/runner.hpp"
#include "harness/suite.hpp"
#include "png_fixture.hpp"

namespace aosuite::harness {
namespace {

namespace fs = std::filesystem;

class SuiteFile : public ::testing::Test {
 protected:
  fs::path write(const std::string& text) {
    const fs::path file = dir_ / "suites" / "s.toml";
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
    return file;
  }
  // The message load_suite throws for `text`, or "" if it loads.
  std::string error_of(const std::string& text) {
    try {
      load_suite(write(text));
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
  test::TempDir dir_;
};

TEST_F(SuiteFile, ExpandsScenesViewsAndTechniquesWithDefaultsAndOverrides) {
  const Suite s = load_suite(write(R"(
[defaults]
width = 64
height = 36
techniques = ["alchemy", "sao"]
params = { samples = 4 }
[defaults.tolerance]
mode = "nothing"
max_mismatch_percent = 1.5

[[case]]
scene = "corner"

[[case]]
scene = "village"
views = ["street"]
techniques = ["mssao"]
name = "wide"
width = 80
params = { radius = 3, level_weights = [1, 0, 0, 0, 0], blur = "none" }
tolerance = { max_channel_delta = 9 }
)"));
  EXPECT_EQ(s.name, "s");
  EXPECT_EQ(s.goldens, (dir_ / "goldens" / "s").lexically_normal());
  ASSERT_EQ(s.cases.size(), 5u);  // corner: 2 views x 2 techniques; village: 1
  EXPECT_EQ(s.cases[0].id, "corner-" + s.cases[0].view + "-alchemy-64x36");
  EXPECT_EQ(s.cases[0].params.samples, 4);
  EXPECT_EQ(s.cases[0].params.radius,
            renderer::default_params(renderer::Technique::kAlchemy).radius);
  EXPECT_EQ(s.cases[1].technique, renderer::Technique::kSao);
  const Case& v = s.cases[4];
  EXPECT_EQ(v.id, "village-street-mssao-80x36-wide");
  EXPECT_EQ(v.params.samples, 4);
  EXPECT_EQ(v.params.radius, 3);
  EXPECT_EQ(v.params.level_weights[1], 0);
  EXPECT_EQ(v.params.blur, renderer::Blur::kNone);
  EXPECT_EQ(v.tolerance.mode, resemble::Mode::kNothing);  // defaults kept where not overridden
  EXPECT_EQ(v.tolerance.max_mismatch_percent, 1.5);
  EXPECT_EQ(v.tolerance.max_channel_delta, 9);
  EXPECT_EQ(v.images, std::vector<std::string>{"with_ao"});
}

TEST_F(SuiteFile, MalformedSuitesNameFileLineAndReason) {
  const std::string file = (dir_ / "suites" / "s.toml").string();
  struct Bad {
    std::string text, line, reason;
  };
  const std::vector<Bad> bad = {
      {"[[case]]\nscene = \"plane\"\nwidth = = 3\n", ":3:", ""},
      {"[[case]]\nscene = \"plane\"\ncolour = 3\n", ":3:", "unknown key 'colour'"},
      {"[[case]]\nscene = \"atlantis\"\n", ":2:", "unknown scene 'atlantis'"},
      {"[[case]]\nscene = \"plane\"\nviews = [\"nope\"]\n", ":3:", "no view 'nope'"},
      {"[[case]]\nscene = \"plane\"\ntechniques = [\"hbao\"]\n", ":3:", "unknown technique"},
      {"[[case]]\nscene = \"plane\"\nparams = { radius = \"big\" }\n", ":3:", "radius=big"},
      {"[[case]]\nscene = \"plane\"\nparams = { spin = 1 }\n", ":3:", "unknown parameter 'spin'"},
      {"[[case]]\nscene = \"plane\"\nwidth = 0\n", ":3:", "width must be 1..16384"},
      {"[[case]]\nscene = \"plane\"\n[[case]]\nscene = \"plane\"\n", ":3:", "duplicate case"},
      {"name = \"x\"\n", ":1:", "at least one [[case]]"},
      {"[[case]]\nscene = \"plane\"\ntolerance = { mode = \"fuzzy\" }\n", ":3:", "fuzzy"},
      {"[[case]]\nscene = \"plane\"\ntolerance = { max_mismatch_percent = 120 }\n",
       ":3:", "0..100"},
      {"[[case]]\nscene = \"plane\"\ntolerance = { mask = \"none.png\" }\n", ":3:", "no mask"},
      {"[[case]]\nviews = [\"above\"]\n", ":1:", "needs scene"},
      {"[[case]]\nscene = \"plane\"\nimages = [\"depth\"]\n", ":3:", "unknown image 'depth'"},
  };
  for (const Bad& b : bad) {
    const std::string msg = error_of(b.text);
    EXPECT_EQ(msg.rfind(file + b.line, 0), 0u) << b.text << " -> " << msg;
    EXPECT_NE(msg.find(b.reason), std::string::npos) << b.text << " -> " << msg;
  }
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
  EXPECT_EQ(accepted_goldens(c, "with_ao", "llvm"),
            (std::vector<fs::path>{c / "with_ao.png", c / "with_ao~a.png", c / "with_ao~b.png"}));
  EXPECT_EQ(accepted_goldens(c, "ao_only", "llvm"),
            std::vector<fs::path>{c / "llvm" / "ao_only.png"});
  EXPECT_EQ(accepted_goldens(c, "ao_only", "other"), std::vector<fs::path>{c / "ao_only.png"});
  EXPECT_TRUE(accepted_goldens(c, "no_ao", "").empty());
  EXPECT_EQ(golden_path(c, "with_ao", "", ""), c / "with_ao.png");
  EXPECT_EQ(golden_path(c, "with_ao", "llvm", "x"), c / "llvm" / "with_ao~x.png");
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
    return judge("with_ao", png_, render_, goldens, t, true);
  }
  test::TempDir dir_;
  cv::Mat render_;
  std::vector<unsigned char> png_;
};

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
  EXPECT_NE(v.message.find("golden is 40x30, render is 30x40"), std::string::npos) << v.message;
}

TEST_F(Judge, MismatchIsMeasuredAgainstTheAllowedPercentage) {
  cv::Mat g = render_.clone();
  g(cv::Rect(0, 0, 4, 3)).setTo(cv::Scalar(200, 0, 0, 255));  // 12 of 1200 pixels: 1 %
  const fs::path file = golden("g.png", g);
  Tolerance t;
  t.max_mismatch_percent = 0.99;
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

TEST_F(Judge, IgnoredBoxesAndMaskBlackPixelsAreNotJudged) {
  cv::Mat g = render_.clone();
  g(cv::Rect(10, 5, 3, 2)).setTo(cv::Scalar(0, 0, 0, 255));
  const fs::path file = golden("g.png", g);
  Tolerance t;
  t.ignore = {{10, 5, 12, 6}};  // inclusive, as Resemble's boxes
  EXPECT_EQ(run({file}, t).status, Status::kPass);
  t.ignore = {{10, 5, 11, 6}};
  EXPECT_EQ(run({file}, t).status, Status::kFail);
  t.ignore.clear();
  cv::Mat mask(render_.size(), CV_8UC4, cv::Scalar(255, 255, 255, 255));
  mask(cv::Rect(10, 5, 3, 2)).setTo(cv::Scalar(0, 0, 0, 255));
  t.mask = golden("mask.png", mask);
  EXPECT_EQ(run({file}, t).status, Status::kPass);
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

TEST(Results, RoundTripThroughJson) {
  CaseResult c;
  c.id = "a-b-sao-8x8", c.scene = "a", c.view = "b", c.technique = "sao", c.width = c.height = 8;
  c.params = {{"radius", "10"}};
  c.tolerance.mode = resemble::Mode::kAntialiasing, c.tolerance.ignore = {{1, 2, 3, 4}};
  c.status = Status::kFail, c.message = "with_ao: mismatch";
  ImageVerdict v;
  v.image = "with_ao", v.status = Status::kFail, v.mismatch_percent = 1.25,
  v.mismatch_text = "1.25";
  v.golden = "g/with_ao.png";
  c.images = {v};
  c.files = {{"with_ao", "a/with_ao.png"}};
  c.times = {{"ao", 1.5}};
  c.input_hash = "12", c.judge_hash = "34";
  RunResults r;
  r.suite = "s", r.gl = "gl", r.platform = "p", r.cases = {c};
  const RunResults back = run_from_json(to_json(r));
  EXPECT_EQ(to_json(back), to_json(r));
  EXPECT_EQ(back.cases[0].tolerance.mode, resemble::Mode::kAntialiasing);
  EXPECT_EQ(exit_code(count(back)), 1);
}

TEST(HtmlReport, LinksTheLatestSweepBesideIt) {
  const test::TempDir dir;
  RunResults r;
  r.suite = "s";
  write_html_report(r, dir.path() / "s");
  auto page = [&] {
    std::ifstream in(dir.path() / "s" / "index.html");
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_NE(page().find("No sweep next to this report"), std::string::npos);
  fs::create_directories(dir.path() / "sweep");
  std::ofstream(dir.path() / "sweep" / "sweep.md") << "| t |";
  std::ofstream(dir.path() / "sweep" / "sweep_320x180.svg") << "<svg/>";
  write_html_report(r, dir.path() / "s");
  EXPECT_NE(page().find("href=\"../sweep/sweep.md\""), std::string::npos);
  EXPECT_NE(page().find("href=\"../sweep/sweep_320x180.svg\""), std::string::npos);
}

TEST(Escape, MarkupCharactersAreEscaped) {
  EXPECT_EQ(escape_markup(R"(<a href="x">'&'</a>)"),
            "&lt;a href=&quot;x&quot;&gt;&#39;&amp;&#39;&lt;/a&gt;");
}

}  // namespace
}  // namespace aosuite::harness

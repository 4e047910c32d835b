// `aosuite tolerances suggest`, end to end: two check runs whose images differ slightly from
// the golden and from each other, the suggestion's exact numbers, and that those limits pass
// both runs' images while tighter ones fail; the margin a held-back run needs, measured on ten
// noisy runs with the suggestion pasted into the suite; bad input is one line, exit 2, nothing
// written.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "compare/opencv.hpp"
#include "harness/suggest_toml.hpp"
#include "harness/tolerance_suggest.hpp"
#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;

// An 8x6 grey chart with `changed` pixels of the first row brightened in red by the deltas.
cv::Mat chart(std::initializer_list<int> deltas) {
  cv::Mat m(6, 8, CV_8UC4, cv::Scalar(100, 100, 100, 255));
  int x = 0;
  for (int d : deltas) m.at<cv::Vec4b>(0, x++)[0] = static_cast<unsigned char>(100 + d);
  return m;
}

class TolerancesSuggest : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "s");
    // The "renderer" copies the picture run.txt names: the golden, then two runs that each
    // drift a little (run a: 1 pixel by 5; run b: 2 pixels, by 3 and 7).
    write_png_rgba8(dir_ / "s" / "golden.png", chart({}));
    write_png_rgba8(dir_ / "s" / "a.png", chart({5}));
    write_png_rgba8(dir_ / "s" / "b.png", chart({3, 7}));
    write_png_rgba8(dir_ / "s" / "photo.png", chart({}));
    std::ofstream(dir_ / "s" / "draw.sh")
        << "cp \"$2/$(cat \"$2/run.txt\").png\" \"$1/chart.png\"\n";
    write_suite(
        "mode = \"nothing\"\nmax_mismatch_percent = 50\nmax_channel_delta = 64\n"
        "flip = { max_mean = 0.5 }\n");
  }
  void write_suite(const std::string& tolerance, const std::string& name = "t") {
    std::ofstream(dir_ / "s" / (name + ".toml")) << "[defaults.tolerance]\n"
                                                 << tolerance << R"(
[[case]]
name = "chart"
command = ["sh", "{suite_dir}/draw.sh", "{out}", "{suite_dir}"]
outputs = ["chart.png"]
inputs = ["draw.sh", "run.txt"]

[[case]]
name = "photo"
files = ["photo.png"]
)";
  }
  void draw(const std::string& run) { std::ofstream(dir_ / "s" / "run.txt") << run; }
  test::Outcome aosuite(const std::string& args) {
    return test::run_shell("cd " + dir_.path().string() + " && " + AOSUITE_BIN + " " + args,
                           dir_.path());
  }
  // Blesses the golden, then checks run a (both cases, or `first` as a --filter) and run b (the
  // chart only).
  void two_runs(const std::string& first = "") {
    const std::string filter = first.empty() ? "" : " --filter '" + first + "'";
    draw("golden");
    ASSERT_EQ(aosuite("bless s/t.toml" + filter).rc, 0);
    draw("a");
    ASSERT_EQ(aosuite("check s/t.toml --report reports/a" + filter).rc, 0);
    draw("b");
    ASSERT_EQ(aosuite("check s/t.toml --filter '^chart$' --report reports/b").rc, 0);
  }
  // The chart's FLIP mean in a run, as its results.json keeps it.
  double flip_mean(const std::string& report) {
    const nlohmann::json r =
        nlohmann::json::parse(test::read_text(dir_ / "reports" / report / "results.json"));
    for (const nlohmann::json& c : r.at("cases"))
      if (c.at("id") == "chart") return c.at("images").at(0).at("metrics").at("flip").at("mean");
    ADD_FAILURE() << "no chart in " << report;
    return 0;
  }
  // Written into the last report given, never among the goldens.
  fs::path suggested() const { return dir_ / "reports" / "b" / "tolerances.suggested.toml"; }
  test::TempDir dir_;
};

TEST(RoundOutward, FourSignificantDigitsNeverInsideTheValue) {
  EXPECT_EQ(harness::round_outward(100.0 / 48, true), 2.084);
  EXPECT_EQ(harness::round_outward(0.0625, true), 0.0625);  // exact: kept
  EXPECT_EQ(harness::round_outward(0.99987654, false), 0.9998);
  EXPECT_EQ(harness::round_outward(123456, true), 123500);
  EXPECT_EQ(harness::round_outward(0, true), 0);
  for (double v : {1.0 / 3, 2.0 / 3, 1e-7 / 3, 0.1 + 0.2, 100.0 / 3072}) {
    EXPECT_GE(harness::round_outward(v, true), v);
    EXPECT_LE(harness::round_outward(v, false), v);
  }
}

// With --margin 0 the suggestion is the largest of what both runs measured, in the suite's
// keys; put into the suite it passes both runs' images, and one step tighter it fails the run
// that set it.
// A [[case]] that expands into several ids (a scene case's views and techniques) has one
// [case.tolerance] for all of them: the suggestion file gives it one table, the loosest of its
// ids' suggestions, naming each id and its margin; another [[case]]'s id keeps its own table.
TEST(SuggestionsToml, TheIdsOfOneCaseTableGetOneToleranceTheLoosest) {
  harness::Suite suite;
  suite.name = "s", suite.file = "s/t.toml";
  for (const auto& [id, table] : {std::pair{"a-gtao", 0}, {"a-sao", 0}, {"b", 1}}) {
    harness::Case k;
    k.id = id, k.table = table;
    suite.cases.push_back(k);
  }
  const auto suggestion = [](const char* id, double mismatch, int delta) {
    harness::Suggestion s;
    s.id = id, s.runs = {"r1", "r2"}, s.margin_why = "--margin";
    s.current.max_mismatch_percent = 50, s.current.max_channel_delta = 64;
    s.proposed = s.current;
    s.proposed.max_mismatch_percent = mismatch, s.proposed.max_channel_delta = delta;
    return s;
  };
  const std::string toml = harness::suggestions_toml(
      suite, {suggestion("a-gtao", 1.5, 9), suggestion("a-sao", 2.5, 4), suggestion("b", 0.5, 3)},
      {"r1", "r2"}, {});
  std::size_t tables = 0;
  for (std::size_t at = 0; (at = toml.find("[case.tolerance]\n", at)) != std::string::npos; ++at)
    ++tables;
  EXPECT_EQ(tables, 2u) << toml;
  EXPECT_NE(toml.find("\n# a-gtao, a-sao: one [[case]], so one [case.tolerance], the loosest of "
                      "their suggestions:\n"
                      "#   a-gtao, from 2 runs: +0 % on each limit, --margin\n"
                      "#   a-sao, from 2 runs: +0 % on each limit, --margin\n"
                      "[case.tolerance]\nmode = \"less\"\n"
                      "max_mismatch_percent = 2.5  # now 50\nmax_channel_delta = 9  # now 64\n"),
            std::string::npos)
      << toml;
  EXPECT_NE(toml.find("\n# b, from 2 runs: +0 % on each limit, --margin\n[case.tolerance]\n"
                      "mode = \"less\"\nmax_mismatch_percent = 0.5  # now 50\n"
                      "max_channel_delta = 3  # now 64\n"),
            std::string::npos)
      << toml;
}

TEST_F(TolerancesSuggest, TheTightestLimitsPassingEveryRun) {
  two_runs();
  const test::Outcome r =
      aosuite("tolerances suggest s/t.toml --report reports/a --report reports/b --margin 0");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;  // photo was seen in one run only
  const double flip = harness::round_outward(std::max(flip_mean("a"), flip_mean("b")), true);
  ASSERT_GT(flip, 0);
  const std::string toml = test::read_text(suggested());
  for (const std::string& line :
       {std::string("# chart, from 2 runs: +0 % on each limit, --margin\n[case.tolerance]\n"),
        std::string("mode = \"nothing\"\n"),
        std::string("max_mismatch_percent = 4.167  # now 50\n"),  // 2 of 48 pixels
        std::string("max_channel_delta = 7  # now 64\n"),
        fmt::format("flip = {{ max_mean = {} }}  # now {{ max_mean = 0.5 }}\n", flip),
        std::string("#   photo: seen in one run (reports/a); a suggestion needs two or more\n")}) {
    EXPECT_NE(toml.find(line), std::string::npos) << line << "in\n" << toml;
  }
  EXPECT_NE(toml.find("from 2 runs:\n#   reports/a\n#   reports/b\n"), std::string::npos) << toml;
  EXPECT_NE(r.out.find("max Δ 64 -> 7"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("suggested tolerances for 1 of 2 cases from 2 runs"), std::string::npos);

  const auto check_both = [&](const std::string& tolerance) {
    write_suite(tolerance);
    std::vector<int> rcs;
    for (const char* run : {"a", "b"}) {
      draw(run);
      rcs.push_back(
          aosuite(fmt::format("check s/t.toml --filter '^chart$' --report reports/v{}", run)).rc);
    }
    return rcs;
  };
  const auto tolerance = [&](double mismatch, int delta, double flip_max) {
    return fmt::format(
        "mode = \"nothing\"\nmax_mismatch_percent = {}\nmax_channel_delta = {}\n"
        "flip = {{ max_mean = {} }}\n",
        mismatch, delta, flip_max);
  };
  EXPECT_EQ(check_both(tolerance(4.167, 7, flip)), (std::vector{0, 0}));
  EXPECT_EQ(check_both(tolerance(4.166, 7, flip)), (std::vector{0, 1}));
  EXPECT_EQ(check_both(tolerance(4.167, 6, flip)), (std::vector{0, 1}));
  const std::vector<int> tighter_flip = check_both(tolerance(4.167, 7, flip * 0.999));
  EXPECT_EQ(tighter_flip[flip_mean("a") > flip_mean("b") ? 0 : 1], 1);
}

// --margin widens each limit by a share of what was measured, before rounding outward.
TEST_F(TolerancesSuggest, AMarginIsAddedToWhatWasMeasured) {
  two_runs();
  ASSERT_EQ(aosuite("tolerances suggest s/t.toml --report reports/a --report reports/b "
                    "--margin 10 --out margin.toml")
                .rc,
            1);
  const std::string toml = test::read_text(dir_ / "margin.toml");
  EXPECT_NE(toml.find("max_mismatch_percent = 4.584  # now 50\n"), std::string::npos) << toml;
  EXPECT_NE(toml.find("max_channel_delta = 8  # now 64\n"), std::string::npos) << toml;
  EXPECT_NE(toml.find("The margin is 10 % (--margin)."), std::string::npos) << toml;
  EXPECT_FALSE(fs::exists(suggested()));
}

// Without --margin each run is held back in turn: run b, against the limits run a alone sets,
// needs them about doubled (2 pixels against 1, steps of 7 against 5). That widest widening is
// the margin of every limit that varied, stated in the file and the summary; the file goes
// into the last report folder, not among the goldens.
TEST_F(TolerancesSuggest, TheDefaultMarginIsWhatAHeldBackRunNeeded) {
  two_runs();
  const test::Outcome r =
      aosuite("tolerances suggest s/t.toml --report reports/a --report reports/b");
  EXPECT_EQ(r.rc, 1) << r.out << r.err;
  const std::string toml = test::read_text(suggested());
  const std::string head = "# chart, from 2 runs: ";
  const std::size_t at = toml.find(head);
  ASSERT_NE(at, std::string::npos) << toml;
  const std::string margin = toml.substr(at + head.size(), toml.find('\n', at) - at - head.size());
  EXPECT_TRUE(margin.starts_with("+")) << margin;
  EXPECT_NE(margin.find(" % on each limit, the farthest a held-back run fell from the others' "
                        "limit ("),
            std::string::npos)
      << margin;
  EXPECT_TRUE(margin.ends_with(" in reports/b)")) << margin;
  // Run b's 4.167 % against run a's 2.084 % (rounded up) alone needs +99.94 %.
  const double percent = std::stod(margin.substr(1));
  EXPECT_GE(percent, 99.93) << margin;
  EXPECT_NE(toml.find(fmt::format("[case.tolerance]\nmode = \"nothing\"\n"), at),
            std::string::npos);
  EXPECT_NE(toml.find(fmt::format("max_channel_delta = {}  # now 64\n",
                                  int(std::ceil(7 * (1 + percent / 100))))),
            std::string::npos)
      << toml;
  EXPECT_NE(r.out.find(margin), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "s" / "goldens" / "t" / "tolerances.suggested.toml"));
}

// A noisy renderer: each run brightens a random eighth of the pixels by 1 to 12 levels (a
// triangular distribution), from a fixed seed of its own. Suggested from the first four of ten
// runs and pasted into a copy of the suite as it is, the default margin passes the six later
// runs, while the limits without a margin fail at least one: the margin is what makes them hold.
TEST_F(TolerancesSuggest, LaterRunsPassUnderThePastedSuggestion) {
  constexpr int kRuns = 10, kFirst = 4;
  write_suite(  // loose enough for every run: the noise shifts the mean by some 0.8 levels
      "mode = \"nothing\"\nmax_mismatch_percent = 50\nmax_channel_delta = 64\n"
      "max_mean_shift = 8\nmax_mean_delta = 8\nflip = { max_mean = 0.5 }\n");
  const cv::Mat clean(48, 64, CV_8UC4, cv::Scalar(100, 100, 100, 255));
  write_png_rgba8(dir_ / "s" / "golden.png", clean);
  for (int run = 0; run < kRuns; ++run) {
    std::mt19937 rng(43 + run);  // its sequence is the standard's; distributions' are not
    cv::Mat m = clean.clone();
    for (cv::Vec4b& p : cv::Mat_<cv::Vec4b>(m)) {
      if (rng() % 8 != 0) continue;
      const auto step = 1 + rng() % 6;  // one draw a statement: their order is fixed
      p[0] = static_cast<unsigned char>(p[0] + step + rng() % 7);
    }
    write_png_rgba8(dir_ / "s" / fmt::format("r{}.png", run), m);
  }
  draw("golden");
  ASSERT_EQ(aosuite("bless s/t.toml --filter '^chart$'").rc, 0);
  for (int run = 0; run < kRuns; ++run) {
    draw(fmt::format("r{}", run));
    const test::Outcome r =
        aosuite(fmt::format("check s/t.toml --filter '^chart$' --report reports/r{}", run));
    ASSERT_EQ(r.rc, 0) << r.out << r.err;
  }
  const auto suggest_from_first = [&](const std::string& flags) {
    std::string args = "tolerances suggest s/t.toml" + flags;
    for (int run = 0; run < kFirst; ++run) args += fmt::format(" --report reports/r{}", run);
    const test::Outcome r = aosuite(args);
    EXPECT_EQ(r.rc, 1) << r.out << r.err;  // the photo is in no report
    return test::read_text(dir_ / "reports" / fmt::format("r{}", kFirst - 1) /
                           "tolerances.suggested.toml");
  };
  // The chart's table pasted below its [[case]] in a copy of the suite; each later run's status
  // under it.
  const auto later_runs = [&](const std::string& toml, const std::string& tag) {
    std::string suite = test::read_text(dir_ / "s" / "t.toml");
    const std::size_t table = toml.find("[case.tolerance]\n");
    const std::size_t end = toml.find("\n\n", table);
    suite.insert(suite.find("\n[[case]]\nname = \"photo\""),
                 fmt::format("\n{}", std::string_view(toml).substr(table, end - table)));
    std::ofstream(dir_ / "s" / "pasted.toml") << suite;
    std::vector<int> rcs;
    for (int run = kFirst; run < kRuns; ++run) {
      draw(fmt::format("r{}", run));
      rcs.push_back(aosuite(fmt::format("check s/pasted.toml --goldens s/goldens/t --filter "
                                        "'^chart$' --report reports/{}{}",
                                        tag, run))
                        .rc);
    }
    return rcs;
  };
  const std::string with_margin = suggest_from_first("");
  EXPECT_EQ(later_runs(with_margin, "held"), std::vector<int>(kRuns - kFirst, 0)) << with_margin;
  // The largest step is 12 in every run: it varies not, and gets no margin.
  EXPECT_NE(with_margin.find("#   none on max_channel_delta: the same in every run\n"),
            std::string::npos)
      << with_margin;
  const std::string without = suggest_from_first(" --margin 0");
  EXPECT_NE(std::ranges::count(later_runs(without, "tight"), 1), 0) << without;
}

// A two-sided budget is suggested two-sided: the least and the most each run measured.
TEST_F(TolerancesSuggest, TwoSidedBudgetsKeepBothEnds) {
  write_suite(
      "mode = \"nothing\"\nmax_mismatch_percent = 50\nchannel_delta = [1, 64]\n"
      "differing_pixels = [1, 40]\n");
  two_runs("^chart$");  // the photo is identical: under a minimum of 1 it would fail
  ASSERT_NE(
      aosuite("tolerances suggest s/t.toml --report reports/a --report reports/b --margin 0").rc,
      2);
  const std::string toml = test::read_text(suggested());
  EXPECT_NE(toml.find("channel_delta = [5, 7]  # now [1, 64]\n"), std::string::npos) << toml;
  EXPECT_NE(toml.find("differing_pixels = [1, 2]  # now [1, 40]\n"), std::string::npos) << toml;
  EXPECT_EQ(toml.find("max_channel_delta"), std::string::npos) << toml;
}

// A margin widens a minimum downward, as it widens a maximum upward: a two-sided budget's lower
// end and a metric's min_ limit both drop below the least any run measured.
TEST_F(TolerancesSuggest, AMarginLowersAMinimum) {
  write_suite(
      "mode = \"nothing\"\nmax_mismatch_percent = 50\nchannel_delta = [1, 64]\n"
      "ssim = { min_mean = 0.1 }\n");
  two_runs("^chart$");
  ASSERT_NE(aosuite("tolerances suggest s/t.toml --report reports/a --report reports/b "
                    "--margin 50 --out m.toml")
                .rc,
            2);
  const std::string toml = test::read_text(dir_ / "m.toml");
  EXPECT_NE(toml.find("channel_delta = [2, 11]  # now [1, 64]\n"), std::string::npos) << toml;
  const auto ssim_mean = [&](const std::string& report) {
    const nlohmann::json r =
        nlohmann::json::parse(test::read_text(dir_ / "reports" / report / "results.json"));
    return r.at("cases").at(0).at("images").at(0).at("metrics").at("ssim").at("mean").get<double>();
  };
  const double least = std::min(ssim_mean("a"), ssim_mean("b"));
  const std::size_t at = toml.find("min_mean = ");
  ASSERT_NE(at, std::string::npos) << toml;
  const double proposed = std::stod(toml.substr(at + 11));
  EXPECT_LT(proposed, least) << toml;
  EXPECT_NEAR(proposed, least * 0.5, 1e-3) << toml;
}

// A golden blessed since the runs makes their numbers stale: nothing is suggested from them.
TEST_F(TolerancesSuggest, RunsAgainstAnOlderGoldenAreNotUsed) {
  two_runs();
  ASSERT_EQ(aosuite("bless s/t.toml --force").rc, 0);  // run b's picture is the golden now
  const test::Outcome r =
      aosuite("tolerances suggest s/t.toml --report reports/a --report reports/b");
  EXPECT_EQ(r.rc, 2) << r.out << r.err;
  EXPECT_NE(r.out.find("chart/chart.png changed since (check again)"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(suggested()));
}

// Bad input: one line on stderr naming the file, exit 2, nothing written.
TEST_F(TolerancesSuggest, BadInputIsOneLineAndWritesNothing) {
  two_runs();
  write_suite("max_mismatch_percent = 50\n", "u");
  draw("a");
  aosuite("check s/u.toml --report reports/u");  // NEW: suite u has no goldens
  ASSERT_TRUE(fs::exists(dir_ / "reports" / "u" / "results.json"));
  draw("b");  // a report among the goldens: the file would be written there
  ASSERT_EQ(aosuite("check s/t.toml --filter '^chart$' --report s/goldens/t/rep").rc, 0);
  const std::string a = "tolerances suggest s/t.toml --report reports/a ";
  const struct {
    std::string args, names;
  } bad[] = {
      {a + "--report reports/missing", "reports/missing/results.json"},
      {a + "--report reports/u", "reports/u/results.json: a run of suite 'u', not 't'"},
      {a + "--report reports/a", "reports/a/results.json: given twice"},
      {a + "--report s/goldens/t/rep",
       "s/goldens/t/rep/tolerances.suggested.toml: inside the goldens folder"},
      {a, "no case of s/t.toml has two usable runs"},
  };
  for (const auto& b : bad) {
    const test::Outcome r = aosuite(b.args);
    EXPECT_EQ(r.rc, 2) << b.args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(b.names), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(suggested())) << b.args;
  }
  EXPECT_FALSE(fs::exists(dir_ / "s" / "goldens" / "t" / "rep" / "tolerances.suggested.toml"));
}

// Folder mode judges every image by one tolerance, so its suggestion is the folder-mode flags
// of the loosest image's: they pass both runs, and one level or pixel less fails one of them.
TEST_F(TolerancesSuggest, FolderModeRunsGetTheFlagsOfOneTolerance) {
  fs::create_directories(dir_ / "expected" / "sub");
  fs::create_directories(dir_ / "actual" / "sub");
  write_png_rgba8(dir_ / "expected" / "one.png", chart({}));
  write_png_rgba8(dir_ / "expected" / "sub" / "two.png", chart({}));
  const std::string folders = "--actual actual --expected expected";
  const std::string loose = " --max-mismatch 50 --max-channel-delta 64 --gate flip.max_mean=0.5";
  // Run a: one.png off by 5 in one pixel; run b: two.png off by 3 and 7 in two.
  write_png_rgba8(dir_ / "actual" / "one.png", chart({5}));
  write_png_rgba8(dir_ / "actual" / "sub" / "two.png", chart({}));
  ASSERT_EQ(aosuite("check " + folders + loose + " --report reports/a").rc, 0);
  write_png_rgba8(dir_ / "actual" / "one.png", chart({}));
  write_png_rgba8(dir_ / "actual" / "sub" / "two.png", chart({3, 7}));
  ASSERT_EQ(aosuite("check " + folders + loose + " --report reports/b").rc, 0);

  // Each image was changed in one run and the golden in the other, so each stat it has was 0 in
  // one of two runs: no share of 0 reaches the other run's value, and the summary says so.
  const test::Outcome held = aosuite("tolerances suggest --report reports/a --report reports/b");
  ASSERT_EQ(held.rc, 0) << held.out << held.err;
  EXPECT_NE(held.out.find("max_channel_delta: 5 in reports/a, where the other runs set 0, which "
                          "no margin widens: the limit starts from 5"),
            std::string::npos)
      << held.out;
  // Without a margin, Resemble's default mode lets steps this small through (0 %); the largest
  // step is run b's 7, the means the larger of the two runs', and FLIP's mean the larger of the
  // two images'.
  const std::string tightest = " --margin 0";
  const test::Outcome r =
      aosuite("tolerances suggest --report reports/a --report reports/b" + tightest);
  ASSERT_EQ(r.rc, 0) << r.out << r.err;
  const std::string flags =
      "--max-mismatch 0 --max-channel-delta 7 --limit max_mean_shift=0.2084 "
      "--limit max_mean_delta=0.05209 --gate flip.max_mean=0.0073";
  const std::size_t at = r.out.find(flags);
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string line = r.out.substr(r.out.rfind("aosuite check ", at));
  const std::string suggested = line.substr(14, line.find('\n') - 14);
  EXPECT_FALSE(fs::exists(dir_ / "expected" / "tolerances.suggested.toml"));
  // The same from another directory: the runs named the folders relative to theirs.
  fs::create_directories(dir_ / "elsewhere");
  const test::Outcome there = test::run_shell(
      "cd " + (dir_ / "elsewhere").string() + " && " + AOSUITE_BIN +
          " tolerances suggest --report ../reports/a --report ../reports/b" + tightest,
      dir_.path());
  EXPECT_EQ(there.rc, 0) << there.out << there.err;
  EXPECT_NE(there.out.find(flags), std::string::npos) << there.out;

  // Both runs pass under the suggestion (run b is the folders as they are now) ...
  EXPECT_EQ(aosuite("check " + suggested + " --report reports/c").rc, 0) << suggested;
  write_png_rgba8(dir_ / "actual" / "one.png", chart({5}));
  write_png_rgba8(dir_ / "actual" / "sub" / "two.png", chart({}));
  EXPECT_EQ(aosuite("check " + suggested + " --report reports/d").rc, 0) << suggested;
  // ... and a channel budget one level tighter fails run b.
  write_png_rgba8(dir_ / "actual" / "sub" / "two.png", chart({3, 7}));
  std::string tighter = suggested;
  tighter.replace(tighter.find("--max-channel-delta 7"), 21, "--max-channel-delta 6");
  EXPECT_EQ(aosuite("check " + tighter + " --report reports/e").rc, 1) << tighter;

  // A suite's run is no folder-mode run, and folder mode writes nothing.
  const test::Outcome bad = aosuite("tolerances suggest --report reports/a --out x.toml");
  EXPECT_EQ(bad.rc, 2);
  EXPECT_NE(bad.err.find("folder mode takes no --goldens or --out"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace aosuite

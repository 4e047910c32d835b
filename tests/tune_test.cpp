// `aosuite tune`'s parts: the search space (ao/tune_space.hpp) round-trips parameters and
// presets; the search (ao/tune_search.hpp) is deterministic, holds the depth-tap budget and
// finds a known minimum; a whole tune on llvmpipe (ao/tune_run.hpp) never ends worse than the
// defaults it starts from, validates on the scenes it left out, and resumes from its state
// without rendering again.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <set>

#include "ao/preset.hpp"
#include "ao/tune_run.hpp"
#include "common/file_io.hpp"
#include "reference/error_metrics.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene.hpp"

namespace {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;
using aosuite::ao::SearchOptions;
using aosuite::ao::TuneSpace;

// Every technique searches only what it reads; a screen-space one its radius multiplier too, and
// PMI the map from its visibility to AO (intensity and contrast) but not its channel's settings,
// which Table 1 of results.md studies by cost.
TEST(TuneSpace, EveryTechniqueHasDimensionsItReads) {
  for (const rd::TechniqueInfo& t : rd::techniques()) {
    const TuneSpace space(t.id);
    std::set<std::string> keys;
    for (const aosuite::ao::Dimension& d : space.dimensions()) {
      EXPECT_TRUE(rd::applies(*d.spec, t.id)) << d.spec->key;
      keys.insert(std::string(d.spec->key));
    }
    EXPECT_FALSE(keys.count("radius")) << "the radius is the study's";
    if (t.space == rd::Space::kScreen) {
      EXPECT_TRUE(keys.count("radius_scale")) << t.name;
    }
  }
  EXPECT_EQ(TuneSpace(rd::Technique::kPmi).dimensions().size(), 2u);
}

// Every technique has a built-in tuned preset holding exactly what the tuner searches for it.
TEST(TuneSpace, EveryTechniqueHasABuiltInTunedPreset) {
  for (const rd::TechniqueInfo& t : rd::techniques()) {
    const aosuite::ao::Preset preset = aosuite::ao::find_preset("tuned", t.id);
    std::set<std::string> keys;
    const TuneSpace space(t.id);
    for (const aosuite::ao::Dimension& d : space.dimensions())
      keys.insert(std::string(d.spec->key));
    std::set<std::string> held;
    for (const auto& [key, value] : preset.params) held.insert(key);
    EXPECT_EQ(held, keys) << t.name;
    rd::AoParams p = rd::default_params(t.id);
    aosuite::ao::apply_preset(preset, t.id, p);
    EXPECT_NO_THROW(rd::check_params(p)) << t.name;
  }
}

// The built-in tuned presets mean the same at every scene scale (issue 45): every length they
// set is a share of the radius or of the view, so a scene, its near plane and the radius scaled
// together by 2^-17 or 2^17 (exact in float) give scale 1's AO. A preset length left in scene
// units (bitmask's thickness of 1.09 units, before it became a share of the radius) moves
// the AO by far more than the 1e-4 allowed.
TEST(TuneSpace, TheTunedPresetsGiveTheSameAoAtEveryScale) {
  rd::Renderer renderer;
  const auto scene = [](const std::string& name, float scale) {
    rd::Scene s = rd::builtin_scene(name);
    rd::scale_scene(s, scale);
    for (rd::View& v : s.views) v.near = 0.01f * scale;
    return s;
  };
  for (const rd::TechniqueInfo& t : rd::techniques()) {
    if (t.space != rd::Space::kScreen) continue;  // PMI's maps are per object, not per pixel
    rd::RenderSettings rs;
    rs.width = 96, rs.height = 54, rs.technique = t.id;
    rs.params = rd::default_params(t.id);
    aosuite::ao::apply_preset(aosuite::ao::find_preset("tuned", t.id), t.id, rs.params);
    rs.outputs = rd::Outputs{false, false, false, true};
    const float radius = 0.5f;
    for (const char* name : {"corner", "village"}) {
      rs.params.radius = radius;
      const rd::Scene one_scene = scene(name, 1);
      const cv::Mat one = renderer.render(one_scene, one_scene.views[0], rs).ao.clone();
      for (float scale : {std::ldexp(1.0f, -17), std::ldexp(1.0f, 17)}) {
        rs.params.radius = radius * scale;
        const rd::Scene scaled = scene(name, scale);
        const cv::Mat ao = renderer.render(scaled, scaled.views[0], rs).ao;
        EXPECT_LE(cv::norm(one, ao, cv::NORM_INF), 1e-4) << t.name << " " << name << " " << scale;
      }
    }
  }
}

TEST(TuneSpace, PointsRoundTripThroughParametersAndPresetFiles) {
  const fs::path dir = fs::temp_directory_path() / "aosuite_tune_space";
  fs::create_directories(dir);
  cv::RNG rng(7);
  for (const rd::TechniqueInfo& info : rd::techniques()) {
    const rd::Technique t = info.id;
    const TuneSpace space(t);
    for (int i = 0; i < 20; ++i) {
      std::vector<double> p(space.dimensions().size());
      for (double& x : p) x = rng.uniform(0.0, 1.0);
      const rd::AoParams params = space.params(p, rd::default_params(t));
      // The point of rounded parameters stands for the same parameters.
      EXPECT_EQ(space.key(space.params(space.point(params), rd::default_params(t))),
                space.key(params));
      // A preset written from them reads back to them.
      const aosuite::ao::Preset written{dir / "p.toml", t, space.entries(params)};
      aosuite::ao::write_preset(written, {"a comment"});
      rd::AoParams read = rd::default_params(t);
      aosuite::ao::apply_preset(aosuite::ao::read_preset(dir / "p.toml"), t, read);
      EXPECT_EQ(space.key(read), space.key(params)) << rd::technique_name(t);
      EXPECT_NO_THROW(rd::check_params(read));
    }
  }
  fs::remove_all(dir);
}

// The shrink toward the defaults moves in the search's coordinates: the ends are the two
// parameter sets themselves, and halfway a log-scaled parameter (bitmask's thickness, 0.04..8;
// the intensity, 0.25..4) is their geometric mean, to the three digits kept.
TEST(TuneSpace, BetweenMovesAShareOfTheWayInSearchCoordinates) {
  const TuneSpace space(rd::Technique::kBitmask);
  rd::AoParams from = rd::default_params(rd::Technique::kBitmask), to = from;
  from.bitmask.thickness = 0.1f, to.bitmask.thickness = 1.6f;
  from.intensity = 1, to.intensity = 2;
  EXPECT_EQ(space.key(space.between(from, to, 0)), space.key(from));
  EXPECT_EQ(space.key(space.between(from, to, 1)), space.key(to));
  const rd::AoParams mid = space.between(from, to, 0.5);
  EXPECT_NEAR(mid.bitmask.thickness, 0.4, 0.4 * 5e-3);  // sqrt(0.1 * 1.6)
  EXPECT_NEAR(mid.intensity, std::sqrt(2.0), 5e-3);
}

// A bowl over GTAO's space with its minimum at a known point: the search must get close to
// it, never measure a point over the budget or the same parameters twice, and give the same
// answer for the same seed.
TEST(TuneSearch, FindsAKnownMinimumWithinTheBudgetDeterministically) {
  const TuneSpace space(rd::Technique::kGtao);
  // 0.3 along every dimension, as the space can hold it (a whole number rounds, a switch is off).
  const rd::AoParams base = rd::default_params(rd::Technique::kGtao);
  const std::vector<double> target =
      space.point(space.params(std::vector<double>(space.dimensions().size(), 0.3), base));
  auto distance = [&](const rd::AoParams& p) {
    const std::vector<double> x = space.point(p);
    double e = 0;
    for (std::size_t i = 0; i < x.size(); ++i) e += (x[i] - target[i]) * (x[i] - target[i]);
    return e;
  };
  std::set<std::string> measured;
  auto bowl = [&](const rd::AoParams& p) {
    EXPECT_LE(aosuite::ao::depth_taps(space, p), 12);
    EXPECT_TRUE(measured.insert(space.key(p)).second) << "measured twice: " << space.key(p);
    return distance(p);
  };
  SearchOptions o;
  o.trials = 120, o.budget_taps = 12, o.seed = 3;
  const rd::AoParams start = base;
  const double at_start = distance(start);
  int calls = 0;
  const aosuite::ao::SearchResult a =
      aosuite::ao::search(space, start, o, bowl, [&](int trial, double) { calls = trial; });
  EXPECT_EQ(a.trials, calls);
  EXPECT_LE(a.trials, o.trials);
  EXPECT_LT(a.error, at_start / 10);
  EXPECT_LT(a.error, 0.02);
  measured.clear();
  const aosuite::ao::SearchResult b = aosuite::ao::search(space, start, o, bowl);
  EXPECT_EQ(space.key(a.best), space.key(b.best));
  EXPECT_EQ(a.error, b.error);
  o.budget_taps = 1;  // no GTAO configuration has fewer than 2 taps
  EXPECT_THROW(aosuite::ao::search(space, start, o, bowl), std::invalid_argument);
}

// The pattern search's steps are fractions of a range: one that rounds a whole-number parameter
// back to its value moves it one whole step instead, so GTAO's 0/1 exact_plane switch flips.
TEST(TuneSearch, MovesAWholeNumberParameterAtLeastOneStep) {
  const TuneSpace space(rd::Technique::kGtao);
  SearchOptions o;
  o.trials = 40, o.random_share = 0;  // the pattern search alone, from the defaults
  o.budget_taps = 64;
  const aosuite::ao::SearchResult r = aosuite::ao::search(
      space, rd::default_params(rd::Technique::kGtao), o, [](const rd::AoParams& p) {
        return (1.0 - p.gtao.exact_plane) + 0.01 * std::abs(p.gtao.steps - 4);
      });
  EXPECT_EQ(r.best.gtao.exact_plane, 1);
  EXPECT_EQ(r.best.gtao.steps, 4);  // 3 to 4: under a quarter of the range, one whole step
  EXPECT_DOUBLE_EQ(r.error, 0);
}

TEST(TuneSearch, StartsFromTheGivenParameters) {
  const TuneSpace space(rd::Technique::kSao);
  const rd::AoParams start = rd::default_params(rd::Technique::kSao);
  std::string first;
  SearchOptions o;
  o.trials = 3;
  aosuite::ao::search(space, start, o, [&](const rd::AoParams& p) {
    if (first.empty()) first = space.key(p);
    return 1.0;
  });
  EXPECT_EQ(first, space.key(start));

  // UE4's defaults (8 directions: 48 taps) start at their nearest affordable version, 3.
  const TuneSpace ue4(rd::Technique::kUe4);
  rd::AoParams lowered = rd::default_params(rd::Technique::kUe4);
  first.clear();
  aosuite::ao::search(ue4, lowered, o, [&](const rd::AoParams& p) {
    if (first.empty()) first = ue4.key(p);
    return 1.0;
  });
  lowered.samples = 3;
  EXPECT_EQ(first, ue4.key(lowered));
}

TEST(TuneMetric, MaskedRmseIsTheErrorReportsRmse) {
  cv::RNG rng(11);
  for (int i = 0; i < 10; ++i) {
    cv::Mat a(40, 50, CV_32F), b(40, 50, CV_32F), depth(40, 50, CV_32F);
    rng.fill(a, cv::RNG::UNIFORM, 0, 1), rng.fill(b, cv::RNG::UNIFORM, 0, 1);
    rng.fill(depth, cv::RNG::UNIFORM, -1, 3);  // some background (<= 0)
    const auto report = aosuite::reference::measure_error(a, b, depth, {8, 0.05f, 64});
    EXPECT_NEAR(aosuite::reference::masked_rmse(a, b, aosuite::reference::geometry_mask(depth, 8)),
                report.all.rmse, 1e-8);  // cv::norm sums float differences
  }
}

// A pair's ratio keeps a floor of 1e-3 on both errors, so an exact default (an open plane) gives
// a large but finite ratio; the objective averages the worst ratio and the mean.
TEST(TuneChoice, RatioAndObjective) {
  EXPECT_DOUBLE_EQ(aosuite::ao::error_ratio(0, 0), 1);
  EXPECT_DOUBLE_EQ(aosuite::ao::error_ratio(0.02, 0.02), 1);
  EXPECT_DOUBLE_EQ(aosuite::ao::error_ratio(0.002, 0.001), 1.5);
  EXPECT_DOUBLE_EQ(aosuite::ao::objective({1, 1, 1}), 1);
  EXPECT_DOUBLE_EQ(aosuite::ao::objective({0.5, 1.5}), 0.5 * (1.5 + 1.0));
  EXPECT_DOUBLE_EQ(aosuite::ao::objective({}), 1);
}

// The bar counts whole pairs (29 of 100 is within 0.29, whatever 0.29 x 100 rounds to), a tie
// with the defaults is not worse, a ratio over the limit or not a number is out; the mean is
// geometric and its standard error the log ratios' sample deviation over sqrt(n).
TEST(TuneChoice, SummariseCountsWholePairsAndTheWorst) {
  using aosuite::ao::ShrinkTrial;
  ShrinkTrial t;
  const std::vector<double> ratios = {0.9, 1.02, 0.8, 1.0};
  aosuite::ao::summarise(t, ratios, {0.25, 1.05});
  EXPECT_EQ(t.pairs, 4);
  EXPECT_EQ(t.worse, 1);
  EXPECT_DOUBLE_EQ(t.worst_ratio, 1.02);
  double mean = 0, squares = 0;
  for (double r : ratios) mean += std::log(r) / 4;
  for (double r : ratios) squares += (std::log(r) - mean) * (std::log(r) - mean);
  EXPECT_NEAR(t.mean_ratio, std::exp(mean), 1e-15);
  EXPECT_NEAR(t.log_se, std::sqrt(squares / 3) / 2, 1e-15);
  EXPECT_TRUE(t.within_bar);
  aosuite::ao::summarise(t, ratios, {0.2, 1.05});  // 0.8 of a pair: none may be worse
  EXPECT_FALSE(t.within_bar);
  aosuite::ao::summarise(t, ratios, {1, 1.01});  // 1.02 is over the ratio limit
  EXPECT_FALSE(t.within_bar);
  std::vector<double> hundred(100, 0.9);
  std::fill_n(hundred.begin(), 29, 1.01);
  aosuite::ao::summarise(t, hundred, {0.29, 1.05});
  EXPECT_EQ(t.worse, 29);
  EXPECT_TRUE(t.within_bar);
  aosuite::ao::summarise(t, {0.9, std::nan("")}, {1, 100});
  EXPECT_EQ(t.worse, 1);
  EXPECT_FALSE(t.within_bar);
}

// The share: the smallest eligible one (within the bar and the budget) whose mean log ratio is
// within one standard error of the best eligible mean; the defaults when the best gain is
// within its own standard error.
TEST(TuneChoice, TheSmallestShareWithinOneStandardErrorOfTheBest) {
  using aosuite::ao::ShrinkTrial;
  const auto trial = [](double shrink, double mean, double se, bool bar = true,
                        bool budget = true) {
    ShrinkTrial t;
    t.shrink = shrink, t.mean_ratio = mean, t.log_se = se, t.within_bar = bar;
    t.within_budget = budget;
    return t;
  };
  const ShrinkTrial zero = trial(0, 1, 0);
  EXPECT_EQ(aosuite::ao::choose_shrink({}), 1);
  // A gain of 1 % with a standard error of 2 %: no evidence.
  EXPECT_EQ(aosuite::ao::choose_shrink({zero, trial(0.5, 0.99, 0.02)}), 0);
  // The best mean (share 1) is over the bar: the best eligible is 0.5.
  EXPECT_EQ(aosuite::ao::choose_shrink({zero, trial(0.5, 0.9, 0.01), trial(1, 0.8, 0.01, false)}),
            0.5);
  // Share 0.5 is within one standard error of the best (share 1), share 0.25 is not.
  const std::vector<ShrinkTrial> graded = {zero, trial(0.25, 0.92, 0.01), trial(0.5, 0.91, 0.02),
                                           trial(1, 0.9, 0.02)};
  EXPECT_EQ(aosuite::ao::choose_shrink(graded), 0.5);
  // Over the depth-tap budget, 0.5 is passed over for the next within reach.
  std::vector<ShrinkTrial> costly = graded;
  costly[2].within_budget = false;
  EXPECT_EQ(aosuite::ao::choose_shrink(costly), 1);
  // Nothing better than the defaults: the defaults.
  EXPECT_EQ(aosuite::ao::choose_shrink({zero, trial(0.5, 1.01, 0.001)}), 0);
}

class TuneRun : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("aosuite_tune_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    setenv("AOSUITE_REFERENCE_CACHE", (dir_ / "refs").c_str(), 1);
    s_.technique = rd::Technique::kGtao;
    s_.scenes = {"corner", "spheres"};
    s_.radii = {0.5f, 1};
    s_.width = 64, s_.height = 36, s_.rays = 16;
    s_.search.trials = 8;
    s_.state = dir_ / "state.json";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  aosuite::ao::TuneSettings s_;
};

TEST_F(TuneRun, NeverWorseThanTheDefaultsAndValidatedOnEachSceneLeftOut) {
  int progress = 0;
  const aosuite::ao::TuneResult r =
      aosuite::ao::run_tune(s_, [&](const aosuite::ao::TuneProgress& p) {
        // A candidate is judged by its error over the defaults': the search starts from them.
        if (progress++ == 0) {
          EXPECT_DOUBLE_EQ(p.best, 1);
        }
        EXPECT_LE(p.best, 1);
      });
  EXPECT_GT(progress, 0);
  // GTAO's defaults fit the default budget and are the search's start.
  EXPECT_LE(r.tuned_error, r.default_error);
  EXPECT_GT(r.default_error, 0);
  EXPECT_LE(r.tuned_taps, s_.search.budget_taps);
  ASSERT_EQ(r.folds.size(), 2u);
  EXPECT_EQ(r.folds[0].held_out, "corner");
  EXPECT_EQ(r.folds[1].held_out, "spheres");
  for (const aosuite::ao::Fold& f : r.folds) {
    ASSERT_EQ(f.tuned_error.size(), 2u);
    for (double e : f.tuned_error) EXPECT_TRUE(std::isfinite(e) && e > 0 && e < 1);
    for (double e : f.default_error) EXPECT_TRUE(std::isfinite(e) && e > 0 && e < 1);
  }
  EXPECT_GT(r.renders, 0);
  EXPECT_GT(r.tuned_ms, 0);
  // A fold's errors are its held-out scene's: the defaults' error on "corner" alone is the first
  // fold's (measured on its training scene instead, it would be the spheres').
  aosuite::ao::TuneSettings corner = s_;
  corner.scenes = {"corner"};
  corner.state = dir_ / "corner.json";
  const aosuite::ao::TuneResult alone = aosuite::ao::run_tune(corner);
  const auto mean = [](const std::vector<double>& v) { return (v.at(0) + v.at(1)) / 2; };
  EXPECT_NEAR(mean(r.folds[0].default_error), alone.default_error, 1e-9);
  EXPECT_GT(std::abs(mean(r.folds[1].default_error) - alone.default_error), 1e-6);

  // The same settings again: every measurement comes from the state, the answer is the same.
  const aosuite::ao::TuneResult again = aosuite::ao::run_tune(s_);
  EXPECT_EQ(again.renders, 0);
  const TuneSpace space(s_.technique);
  EXPECT_EQ(space.key(again.tuned), space.key(r.tuned));
  EXPECT_EQ(again.tuned_error, r.tuned_error);

  // A state made under other settings is refused, not mixed in.
  s_.rays = 32;
  EXPECT_THROW(aosuite::ao::run_tune(s_), aosuite::FileError);
}

TEST_F(TuneRun, AnInterruptedTuneResumesToTheSameResult) {
  const aosuite::ao::TuneResult whole = aosuite::ao::run_tune(s_);
  fs::remove(s_.state);
  // Stop the first run partway (as Ctrl-C would), then run it again to the end.
  try {
    aosuite::ao::run_tune(s_, [](const aosuite::ao::TuneProgress& p) {
      if (p.stage.rfind("fold 2", 0) == 0) throw std::runtime_error("interrupted");
    });
    FAIL() << "not interrupted";
  } catch (const std::runtime_error&) {
  }
  const aosuite::ao::TuneResult resumed = aosuite::ao::run_tune(s_);
  EXPECT_GT(resumed.reused, 0);
  EXPECT_LT(resumed.renders, whole.renders);
  const TuneSpace space(s_.technique);
  EXPECT_EQ(space.key(resumed.tuned), space.key(whole.tuned));
  EXPECT_EQ(resumed.tuned_error, whole.tuned_error);
}

// A measurement belongs to the scene's content, not its name: a scene file edited between two
// runs is measured again, and the views that did not change are not.
TEST_F(TuneRun, AnEditedSceneIsMeasuredAgain) {
  const auto scene = [&](float height) {
    std::ofstream(dir_ / "s.toml", std::ios::trunc)
        << "name = \"s\"\n[[meshes]]\nplane = 20\n[[meshes]]\nbox = { min = [-1, 0, -1], max = "
           "[1, "
        << height << ", 1] }\n[[views]]\nname = \"v\"\neye = [3, 2, 4]\ntarget = [0, 0.5, 0]\n";
  };
  scene(1);
  s_.scenes = {(dir_ / "s.toml").string(), "corner"};
  s_.radii = {1};
  const aosuite::ao::TuneResult first = aosuite::ao::run_tune(s_);
  EXPECT_EQ(aosuite::ao::run_tune(s_).renders, 0);
  scene(1.5f);
  const aosuite::ao::TuneResult edited = aosuite::ao::run_tune(s_);
  EXPECT_GT(edited.renders, 0);
  EXPECT_LT(edited.renders, first.renders);  // corner's measurements stand
}

// Folds leave a whole family out (issue 45): corner and spheres are both "analytic", so with a
// scene file of family "scan" there are two folds, not three, and the analytic fold searches on
// the scan alone. Each fold's held-out errors are exactly the state file's measurements of its
// own scenes under its parameters (the held-out scenes, not the ones it searched on: measuring
// a fold on its training scenes instead passed every test before this one), and each held-out
// scene is reported apart.
TEST_F(TuneRun, FoldsLeaveAFamilyOutAndAreMeasuredOnIt) {
  std::ofstream(dir_ / "scan.toml")
      << "name = \"statue\"\nfamily = \"scan\"\n[[meshes]]\nplane = 20\n[[meshes]]\n"
         "sphere = { centre = [0, 0.6, 0], radius = 0.6, segments = 12 }\n"
         "[[meshes]]\nbox = { min = [0.5, 0, -0.3], max = [1.1, 1.4, 0.3] }\n"
         "[[views]]\nname = \"v\"\neye = [2, 1.5, 3]\ntarget = [0, 0.5, 0]\n";
  s_.scenes = {"corner", "spheres", (dir_ / "scan.toml").string()};
  s_.radii = {0.5f};
  s_.search.trials = 4;
  const aosuite::ao::TuneResult r = aosuite::ao::run_tune(s_);
  ASSERT_EQ(r.folds.size(), 2u);
  EXPECT_EQ(r.folds[0].held_out, "analytic");
  EXPECT_EQ(r.folds[1].held_out, "scan");
  ASSERT_EQ(r.folds[0].scenes.size(), 2u);
  EXPECT_EQ(r.folds[0].scenes[0].scene, "corner");
  EXPECT_EQ(r.folds[0].scenes[1].scene, "spheres");
  ASSERT_EQ(r.folds[1].scenes.size(), 1u);
  EXPECT_EQ(r.folds[1].scenes[0].scene, "statue");

  const std::vector<unsigned char> bytes = aosuite::read_file(s_.state);
  const nlohmann::json state = nlohmann::json::parse(bytes.begin(), bytes.end());
  // The mean of the state's errors under `params` over the items of `scenes` (item keys are
  // "scene/view/radius/reference key").
  const auto measured = [&](const std::string& params, const std::set<std::string>& scenes) {
    double sum = 0;
    int n = 0;
    for (const auto& [item, e] : state.at("errors").at(params).items()) {
      if (scenes.contains(item.substr(0, item.find('/')))) sum += e.get<double>(), ++n;
    }
    EXPECT_GT(n, 0);
    return sum / n;
  };
  const std::set<std::string> analytic{"corner", "spheres"}, scan{"statue"};
  const aosuite::ao::Fold& a = r.folds[0];
  const aosuite::ao::Fold& b = r.folds[1];
  EXPECT_NEAR(a.tuned_error.at(0), measured(a.params, analytic), 1e-12);
  EXPECT_NEAR(b.tuned_error.at(0), measured(b.params, scan), 1e-12);
  EXPECT_GT(std::abs(b.tuned_error.at(0) - measured(b.params, analytic)), 1e-6);
  for (const aosuite::ao::Fold& f : r.folds) {
    for (const aosuite::ao::HeldOutScene& h : f.scenes) {
      EXPECT_NEAR(h.tuned_error, measured(f.params, {h.scene}), 1e-12) << h.scene;
      EXPECT_GT(h.default_error, 0) << h.scene;
    }
  }
}

// The preset is the search moved toward the defaults by a share chosen on the held-out (scene,
// radius) pairs: among the shares within the bar (few pairs worse, none by much), the smallest
// whose geometric mean ratio is within one standard error of the best's, and the defaults
// themselves unless that beats them: with one trial each search returns where it starts, the
// defaults, so nothing beats them and they are kept.
TEST_F(TuneRun, APresetMustBeatTheDefaultsOnHeldOutPairsWithinTheBarOrIsTheDefaults) {
  const auto check = [&](const aosuite::ao::TuneResult& r) {
    ASSERT_EQ(r.shrink_trials.size(), 9u);  // eighths
    const aosuite::ao::ShrinkTrial& zero = r.shrink_trials.front();
    EXPECT_EQ(zero.shrink, 0);
    EXPECT_DOUBLE_EQ(zero.worst_ratio, 1);  // the defaults against themselves
    EXPECT_DOUBLE_EQ(zero.mean_ratio, 1);
    EXPECT_DOUBLE_EQ(zero.log_se, 0);
    EXPECT_EQ(zero.worse, 0);
    EXPECT_EQ(zero.pairs, 4);  // two folds of one scene, two radii each
    const TuneSpace space(s_.technique);
    EXPECT_EQ(space.key(r.tuned), space.key(space.between(r.defaults, r.searched, r.shrink)));
    const auto chosen =
        std::ranges::find(r.shrink_trials, r.shrink, &aosuite::ao::ShrinkTrial::shrink);
    ASSERT_NE(chosen, r.shrink_trials.end());
    EXPECT_TRUE(chosen->within_bar);
    // Each trial's figures are its held-out pairs': with one scene a fold, a pair's error is the
    // fold's error at that radius (measured on the training scene instead, they would differ).
    for (const aosuite::ao::ShrinkTrial& t : r.shrink_trials) {
      std::vector<double> ratios;
      for (std::size_t f = 0; f < t.fold_error.size(); ++f) {
        std::vector<double> fold;
        for (std::size_t k = 0; k < s_.radii.size(); ++k)
          fold.push_back(aosuite::ao::error_ratio(t.fold_error[f][k], zero.fold_error[f][k]));
        aosuite::ao::ShrinkTrial one;
        aosuite::ao::summarise(one, fold, s_.bar);
        EXPECT_NEAR(t.fold_ratio.at(f), one.mean_ratio, 1e-12) << t.shrink;
        ratios.insert(ratios.end(), fold.begin(), fold.end());
      }
      aosuite::ao::ShrinkTrial all;
      aosuite::ao::summarise(all, ratios, s_.bar);
      EXPECT_EQ(t.worse, all.worse) << t.shrink;
      EXPECT_NEAR(t.worst_ratio, all.worst_ratio, 1e-12) << t.shrink;
      EXPECT_NEAR(t.mean_ratio, all.mean_ratio, 1e-12) << t.shrink;
      EXPECT_NEAR(t.log_se, all.log_se, 1e-12) << t.shrink;
    }
    if (r.shrink == 0) {
      EXPECT_EQ(space.key(r.searched), space.key(r.defaults)) << "no all-scenes search";
    }
    const aosuite::ao::ShrinkTrial* best = &zero;
    for (const aosuite::ao::ShrinkTrial& t : r.shrink_trials) {
      EXPECT_EQ(t.within_bar,
                t.worse <= s_.bar.worse_share * t.pairs && t.worst_ratio <= s_.bar.worst_ratio);
      ASSERT_EQ(t.fold_ratio.size(), 2u);
      if (t.within_bar && t.mean_ratio < best->mean_ratio) best = &t;
    }
    const double enough = std::log(best->mean_ratio) + best->log_se;
    EXPECT_LE(std::log(chosen->mean_ratio), enough);
    for (const aosuite::ao::ShrinkTrial& t : r.shrink_trials) {
      if (t.shrink < chosen->shrink && t.within_bar) {
        EXPECT_GT(std::log(t.mean_ratio), enough) << t.shrink;
      }
    }
    if (r.shrink > 0) {
      EXPECT_LT(chosen->mean_ratio, 1);
    }
    // A share's held-out errors per fold and radius: the defaults' at 0, the fold's
    // search's at 1.
    for (std::size_t f = 0; f < r.folds.size(); ++f) {
      for (std::size_t k = 0; k < s_.radii.size(); ++k) {
        EXPECT_DOUBLE_EQ(zero.fold_error.at(f).at(k), r.folds[f].default_error.at(k));
        EXPECT_DOUBLE_EQ(r.shrink_trials.back().fold_error.at(f).at(k),
                         r.folds[f].tuned_error.at(k));
      }
    }
  };
  s_.search.trials = 12;
  const aosuite::ao::TuneResult r = aosuite::ao::run_tune(s_);
  check(r);
  // No bar: the lowest mean of all; the strictest: no held-out pair may get worse.
  s_.bar = {1, 100};
  const aosuite::ao::TuneResult loose = aosuite::ao::run_tune(s_);
  check(loose);
  s_.bar = {0, 1};
  const aosuite::ao::TuneResult strict = aosuite::ao::run_tune(s_);
  check(strict);
  const auto at = [](const aosuite::ao::TuneResult& t) {
    return *std::ranges::find(t.shrink_trials, t.shrink, &aosuite::ao::ShrinkTrial::shrink);
  };
  EXPECT_EQ(at(strict).worse, 0);

  s_.search.trials = 1;
  s_.state = dir_ / "one_trial.json";
  const aosuite::ao::TuneResult kept = aosuite::ao::run_tune(s_);
  EXPECT_EQ(kept.shrink, 0);
  const TuneSpace space(s_.technique);
  EXPECT_EQ(space.key(kept.tuned), space.key(kept.defaults));
  EXPECT_EQ(kept.tuned_error, kept.default_error);
}

// PMI is tuned like the others (its map's intensity and contrast, on its cached channel), and a
// scene it cannot draw is left out with the reason instead of ending the tune.
TEST_F(TuneRun, PmiFitsItsMapAndLeavesOutAGroundOnlyScene) {
  s_.technique = rd::Technique::kPmi;
  s_.scenes = {"plane", "corner", "spheres"};
  const aosuite::ao::TuneResult r = aosuite::ao::run_tune(s_);
  ASSERT_EQ(r.left_out.size(), 1u);
  EXPECT_EQ(r.left_out[0].rfind("plane: ", 0), 0u) << r.left_out[0];
  ASSERT_EQ(r.folds.size(), 2u);
  EXPECT_EQ(r.folds[0].held_out, "corner");
  EXPECT_LT(r.tuned_error, r.default_error);  // the paper's pale map is far from AO's scale
  EXPECT_EQ(r.tuned_taps, 0);
  for (const aosuite::ao::Fold& f : r.folds)
    for (double e : f.tuned_error) EXPECT_TRUE(std::isfinite(e) && e > 0 && e < 1);
}

TEST_F(TuneRun, BadSettingsAreRefused) {
  s_.scenes.clear();
  EXPECT_THROW(aosuite::ao::run_tune(s_), std::invalid_argument);
  s_.scenes = {"corner"};
  s_.radii = {0};
  EXPECT_THROW(aosuite::ao::run_tune(s_), std::invalid_argument);
  s_.radii = {1};
  s_.technique = rd::Technique::kPmi;
  s_.scenes = {"plane"};  // ground alone: nothing PMI can draw, so nothing to measure
  try {
    aosuite::ao::run_tune(s_);
    ADD_FAILURE() << "a tune with nothing to measure ran";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("plane: scene 'plane' has no object for pmi"),
              std::string::npos)
        << e.what();
  }
  s_.technique = rd::Technique::kGtao;
  s_.scenes = {"corner"};
  std::ofstream(s_.state) << "{not json";
  EXPECT_THROW(aosuite::ao::run_tune(s_), aosuite::FileError);
}

}  // namespace

// Presets (ao/preset.hpp) where parameters are accepted: `render --preset`, `error --preset`
// and a suite's scene case `preset = "..."`, applied over the technique's defaults and under what
// is given beside them; a preset for another technique or with a bad parameter is a one-line error
// naming the file, and nothing is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "png_fixture.hpp"
#include "process.hpp"
#include "tuned_presets.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;
using test::read_text;
using test::tuned_params;

class Presets : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "g.toml") << "technique = \"gtao\"\n[params]\nslices = 5\n"
                                      "falloff_range = 0.75\n";
  }
  test::Outcome aosuite(const std::string& args, const std::string& env = "") {
    return test::run_shell("cd " + dir_.path().string() + " && " + env + AOSUITE_BIN + " " + args,
                           dir_.path());
  }
  test::TempDir dir_;
};

TEST_F(Presets, RenderAppliesAPresetUnderItsParams) {
  const std::string render =
      "render --scene corner --technique gtao --width 16 --height 9 --outputs with_ao --preset "
      "g.toml ";
  test::Outcome r = aosuite(render + "--param slices=6 --out o");
  ASSERT_EQ(r.rc, 0) << r.err;
  const nlohmann::json params =
      nlohmann::json::parse(read_text(dir_ / "o" / "corner_inside_gtao.json")).at("params");
  EXPECT_EQ(params.at("slices"), 6);                                  // --param wins
  EXPECT_NEAR(params.at("falloff_range").get<double>(), 0.75, 1e-6);  // from the preset
  EXPECT_EQ(params.at("steps"), 3);                                   // the default

  // `error` takes it too, and says which parameters it used.
  r = aosuite(
      "error --scene corner --technique gtao --width 16 --height 9 --preset g.toml "
      "--json --out e");
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out).at("params").at("slices"), 5) << r.out;

  r = aosuite("render --scene corner --technique sao --preset g.toml --out wrong");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("g.toml: a preset for gtao, not sao"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "wrong"));
  std::ofstream(dir_ / "bad.toml") << "technique = \"gtao\"\n[params]\nslicez = 5\n";
  r = aosuite("render --technique gtao --preset bad.toml --out wrong");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("bad.toml:3:10: unknown parameter 'slicez'"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "wrong"));
}

TEST_F(Presets, ASuitesSceneCaseNamesAPreset) {
  const auto suite = [&](const std::string& technique) {
    std::ofstream(dir_ / "p.toml", std::ios::trunc)
        << "[[case]]\nscene = \"corner\"\nviews = [\"inside\"]\ntechniques = [\"" << technique
        << "\"]\nwidth = 16\nheight = 9\npreset = \"g.toml\"\nparams = { steps = 4 }\n";
  };
  suite("gtao");
  test::Outcome r = aosuite("check p.toml");
  ASSERT_EQ(r.rc, 1) << r.out << r.err;  // NEW
  const nlohmann::json params =
      nlohmann::json::parse(read_text(dir_ / "reports" / "p" / "results.json"))
          .at("cases")
          .at(0)
          .at("params");
  EXPECT_EQ(params.at("slices"), 5);  // the preset's
  EXPECT_EQ(params.at("steps"), 4);   // the case's params win
  suite("sao");
  r = aosuite("check p.toml");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("p.toml:7:10: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("a preset for gtao, not sao"), std::string::npos) << r.err;
}

// `tune` writes a preset with the command that made it, `render` takes it, and a tune with
// nothing to measure (PMI on ground alone) is a one-line error that writes nothing.
TEST_F(Presets, TuneWritesAPresetThatRenderTakes) {
  const std::string env = "AOSUITE_REFERENCE_CACHE=" + (dir_ / "refs").string() + " ";
  test::Outcome r = aosuite(
      "tune --technique sao --scenes corner,spheres --radius 1 --width 48 --height 27 --rays 16 "
      "--trials 6 --out t/sao.toml --json t/r.json",
      env);
  ASSERT_EQ(r.rc, 0) << r.err;
  EXPECT_EQ(read_text(dir_ / "t" / "sao.toml")
                .rfind("# Made by `" + std::string(AOSUITE_BIN) + " tune --technique sao", 0),
            0u);
  const nlohmann::json j = nlohmann::json::parse(read_text(dir_ / "t" / "r.json"));
  EXPECT_EQ(j.at("folds").size(), 2u);
  EXPECT_LE(j.at("error").at("tuned").get<double>(), j.at("error").at("default").get<double>());
  EXPECT_NE(r.out.find("AO RMSE on the family left out"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("each scene left out, tuned / default: worst"), std::string::npos) << r.out;

  r = aosuite(
      "render --scene corner --technique sao --preset t/sao.toml --width 16 --height 9 "
      "--outputs with_ao --out o");
  ASSERT_EQ(r.rc, 0) << r.err;
  const nlohmann::json params =
      nlohmann::json::parse(read_text(dir_ / "o" / "corner_inside_sao.json")).at("params");
  // Every "key=value" of the preset's identity is what render used.
  std::istringstream preset(j.at("preset").get<std::string>());
  for (std::string kv; preset >> kv;) {
    const std::string key = kv.substr(0, kv.find('=')), value = kv.substr(kv.find('=') + 1);
    EXPECT_NEAR(params.at(key).get<double>(), std::stod(value), 1e-6) << kv;
  }

  r = aosuite("tune --technique pmi --scenes plane --out t/pmi.toml", env);
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("scene 'plane' has no object for pmi"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "t" / "pmi.toml"));
}

// With no --scenes, tune takes the built-in scenes and the scene files of ./suites/scenes that
// load (the project's meshes), saying which it left out.
TEST_F(Presets, TuneDefaultsToTheBuiltInScenesAndTheProjectsSceneFiles) {
  fs::create_directories(dir_ / "suites" / "scenes");
  std::ofstream(dir_ / "suites" / "scenes" / "good.toml")
      << "[[meshes]]\nplane = 10\n[[meshes]]\nbox = { min = [-1, 0, -1], max = [1, 1, 1] }\n"
         "[[views]]\nname = \"v\"\neye = [3, 2, 4]\ntarget = [0, 0.5, 0]\n";
  std::ofstream(dir_ / "suites" / "scenes" / "bad.toml")
      << "[[meshes]]\nfile = \"missing.ply\"\n[[views]]\nname = \"v\"\neye = [3, 2, 4]\n"
         "target = [0, 0, 0]\n";
  const test::Outcome r = aosuite(
      "tune --technique alchemy --width 32 --height 18 --rays 8 --trials 2 --out t/a.toml "
      "--json t/r.json",
      "AOSUITE_REFERENCE_CACHE=" + (dir_ / "refs").string() + " ");
  ASSERT_EQ(r.rc, 0) << r.err;
  const nlohmann::json scenes = nlohmann::json::parse(read_text(dir_ / "t" / "r.json"))["scenes"];
  for (const char* want :
       {"plane", "corner", "spheres", "village", "workshop", "suites/scenes/good.toml"})
    EXPECT_NE(std::find(scenes.begin(), scenes.end(), want), scenes.end()) << want << scenes;
  EXPECT_EQ(std::find(scenes.begin(), scenes.end(), "suites/scenes/bad.toml"), scenes.end());
  EXPECT_NE(r.err.find("aosuite tune: left out suites/scenes/bad.toml"), std::string::npos)
      << r.err;
}

// A built-in preset is named where a file is: `--preset tuned` is ao/presets/tuned-T.toml for
// every technique, in render and in a suite; an unknown name lists the built-ins.
// `--preset half` is each screen-space technique's defaults with its AO pass at half
// resolution: the render's parameters are the defaults' but half_res, and its passes include
// the downsample and the upsample (docs/rendering.md, "Half-resolution AO").
TEST_F(Presets, TheBuiltInHalfPresetRunsTheAoAtHalfResolution) {
  for (const char* technique : {"alchemy", "sao", "mssao", "ue4", "gtao", "bitmask"}) {
    const test::Outcome r =
        aosuite(std::string("render --scene corner --technique ") + technique +
                " --preset half --width 16 --height 9 --outputs with_ao --out o");
    ASSERT_EQ(r.rc, 0) << technique << r.err;
    const nlohmann::json j = nlohmann::json::parse(
        read_text(dir_ / "o" / ("corner_inside_" + std::string(technique) + ".json")));
    EXPECT_EQ(j.at("params").at("half_res"), 1) << technique;
    ASSERT_EQ(aosuite(std::string("render --scene corner --technique ") + technique +
                      " --width 16 --height 9 --outputs with_ao --out d")
                  .rc,
              0);
    nlohmann::json defaults = nlohmann::json::parse(
        read_text(dir_ / "d" / ("corner_inside_" + std::string(technique) + ".json")))["params"];
    EXPECT_EQ(defaults.at("half_res"), 0) << technique;
    defaults["half_res"] = 1;
    EXPECT_EQ(j.at("params"), defaults) << technique << ": the defaults but half_res";
    EXPECT_TRUE(j.at("median_ms").contains("half_downsample")) << technique;
    EXPECT_TRUE(j.at("median_ms").contains("half_upsample")) << technique;
  }
}

TEST_F(Presets, TheBuiltInTunedPresetIsNamedLikeAFile) {
  for (const char* technique : {"alchemy", "sao", "mssao", "ue4", "gtao", "bitmask", "pmi"}) {
    const test::Outcome r =
        aosuite(std::string("render --scene corner --technique ") + technique +
                " --preset tuned --radius 0.5 --width 16 --height 9 --outputs with_ao --out o");
    ASSERT_EQ(r.rc, 0) << technique << r.err;
    const nlohmann::json params = nlohmann::json::parse(
        read_text(dir_ / "o" / ("corner_inside_" + std::string(technique) + ".json")))["params"];
    if (std::string(technique) != "pmi") {
      EXPECT_EQ(params.at("radius"), 0.5);  // --radius, under the preset
    }
    for (const auto& [key, value] : tuned_params(technique)) {
      const nlohmann::json got = params.at(key);
      ASSERT_EQ(got.is_array(), value.is_array()) << technique << key;
      for (std::size_t i = 0; i < (value.is_array() ? value.size() : 1); ++i) {
        const auto& w = value.is_array() ? value[i] : value;
        EXPECT_NEAR((got.is_array() ? got[i] : got).get<double>(), w.get<double>(), 1e-6)
            << technique << key;
      }
    }
  }
  test::Outcome r = aosuite("render --technique gtao --preset nosuch --out wrong");
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("no built-in preset 'nosuch' for gtao (its built-in ones: half, tuned;"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "wrong"));
  r = aosuite("render --technique pmi --preset half --out wrong");  // object space: no half
  EXPECT_EQ(r.rc, 2);
  EXPECT_NE(r.err.find("no built-in preset 'half' for pmi (its built-in ones: tuned;"),
            std::string::npos)
      << r.err;

  std::ofstream(dir_ / "s.toml") << "[[case]]\nscene = \"corner\"\nviews = [\"inside\"]\n"
                                    "techniques = [\"gtao\", \"sao\"]\nwidth = 16\nheight = 9\n"
                                    "preset = \"tuned\"\n";
  r = aosuite("check s.toml");
  ASSERT_EQ(r.rc, 1) << r.out << r.err;  // NEW
  const nlohmann::json cases =
      nlohmann::json::parse(read_text(dir_ / "reports" / "s" / "results.json")).at("cases");
  ASSERT_EQ(cases.size(), 2u);
  for (const nlohmann::json& c : cases) {
    std::string technique;
    for (const nlohmann::json& l : c.at("labels"))
      if (l.at(0) == "technique") technique = l.at(1);
    EXPECT_NEAR(c.at("params").at("radius_scale").get<double>(),
                tuned_params(technique).at("radius_scale").get<double>(), 1e-6)
        << c;
  }
}

}  // namespace
}  // namespace aosuite

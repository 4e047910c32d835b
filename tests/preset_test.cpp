// Presets (ao/preset.hpp) where parameters are accepted: `render --preset`, `error --preset`
// and a suite's scene case `preset = "..."`, applied over the technique's defaults and under what
// is given beside them; a preset for another technique or with a bad parameter is a one-line error
// naming the file, and nothing is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;
using test::read_text;

class Presets : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "g.toml") << "technique = \"gtao\"\n[params]\nslices = 5\n"
                                      "falloff_range = 0.75\n";
  }
  test::Outcome aosuite(const std::string& args) {
    return test::run_shell("cd " + dir_.path().string() + " && " + AOSUITE_BIN + " " + args,
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

}  // namespace
}  // namespace aosuite

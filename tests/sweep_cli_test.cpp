// `aosuite sweep` on the reduced CI grid and `aosuite error` end to end: every row's errors
// are finite, outputs are written, and bad input exits 2 with a message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "process.hpp"

namespace aosuite::test {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("aosuite_sweep_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
  return cells;
}

// The references go to a fresh cache, so the tracing path runs too.
std::string command(const fs::path& dir, const std::string& args) {
  return "AOSUITE_REFERENCE_CACHE=" + (dir / "cache").string() + " " + AOSUITE_BIN + " " + args;
}

TEST(SweepCli, CiGridHasFiniteErrorsInEveryRow) {
  const fs::path dir = scratch("ci");
  const Outcome o =
      run_shell(command(dir, "sweep " + std::string(AOSUITE_SOURCE_DIR) +
                                 "/suites/sweep_ci.toml --out " + (dir / "out").string()),
                dir);
  ASSERT_EQ(o.rc, 0) << o.err;
  std::ifstream csv(dir / "out" / "sweep.csv");
  std::string line;
  std::getline(csv, line);
  const std::vector<std::string> header = split(line);
  int rows = 0;
  for (; std::getline(csv, line); ++rows) {
    const std::vector<std::string> cells = split(line);
    ASSERT_EQ(cells.size(), header.size()) << line;
    for (std::size_t i = 8; i < cells.size(); ++i) {  // times and errors
      const double v = std::strtod(cells[i].c_str(), nullptr);
      EXPECT_TRUE(std::isfinite(v) && !cells[i].empty()) << header[i] << " in " << line;
    }
  }
  EXPECT_EQ(rows, 4 * 4 * 2);  // four techniques x 2 samples x 2 radii, two views
  const auto j = nlohmann::json::parse(std::ifstream(dir / "out" / "sweep.json"));
  EXPECT_EQ(j["fit_on_one_view"].size(), 4u);
  EXPECT_TRUE(fs::exists(dir / "out" / "sweep_160x90.svg"));
  EXPECT_TRUE(fs::exists(dir / "out" / "sweep_160x90_unbounded.svg"));
  EXPECT_FALSE(fs::is_empty(dir / "cache"));
}

TEST(SweepCli, SceneAndResolutionReplaceTheGrids) {
  const fs::path dir = scratch("scene");
  const Outcome o =
      run_shell(command(dir, "sweep " + std::string(AOSUITE_SOURCE_DIR) +
                                 "/suites/sweep_ci.toml --scene plane --resolution 64x36 --out " +
                                 (dir / "out").string()),
                dir);
  ASSERT_EQ(o.rc, 0) << o.err;
  std::ifstream csv(dir / "out" / "sweep.csv");
  std::string line;
  std::getline(csv, line);
  int rows = 0;
  for (; std::getline(csv, line); ++rows) {
    const std::vector<std::string> cells = split(line);
    EXPECT_EQ(cells.at(0), "plane") << line;
    EXPECT_EQ(cells.at(3) + "x" + cells.at(4), "64x36") << line;
  }
  EXPECT_EQ(rows, 4 * 4 * 2);  // the plane's two views
}

TEST(SweepCli, ErrorPrintsJsonAndWritesTheReference) {
  const fs::path dir = scratch("error");
  const Outcome o = run_shell(
      command(
          dir,
          "error --scene corner --technique sao --width 96 --height 54 --rays 16 --json --out " +
              (dir / "out").string()),
      dir);
  ASSERT_EQ(o.rc, 0) << o.err;
  const auto j = nlohmann::json::parse(o.out);
  EXPECT_EQ(j["reference"]["radius"], 10.0);  // SAO's default radius
  EXPECT_GT(j["error"]["all"]["pixels"].get<int>(), 0);
  for (const char* f : {"reference.exr", "reference.png", "ao.png", "error.png"})
    EXPECT_TRUE(fs::exists(
        dir / "out" /
        (j["scene"].get<std::string>() + "_" + j["view"].get<std::string>() + "_sao_" + f)))
        << f;
}

TEST(SweepCli, BadInputExitsTwo) {
  const fs::path dir = scratch("bad");
  std::ofstream(dir / "bad.toml") << "scenes = [\"village\"]\nresolutions = [[160, 90]]\n"
                                     "[techniques.blurry]\nsamples = [1]\nradius = [1]\n";
  Outcome o = run_shell(command(dir, "sweep " + (dir / "bad.toml").string()), dir);
  EXPECT_EQ(o.rc, 2);
  EXPECT_NE(o.err.find("bad.toml"), std::string::npos) << o.err;
  o = run_shell(command(dir, "sweep " + std::string(AOSUITE_SOURCE_DIR) +
                                 "/suites/sweep_ci.toml --scene atlantis"),
                dir);
  EXPECT_EQ(o.rc, 2);
  EXPECT_NE(o.err.find("atlantis"), std::string::npos) << o.err;
  o = run_shell(command(dir, "error --technique alchemy --variant bent --width 32 --height 18"),
                dir);
  EXPECT_EQ(o.rc, 2);
  EXPECT_NE(o.err.find("bent"), std::string::npos) << o.err;
}

}  // namespace
}  // namespace aosuite::test

// `aosuite sweep` on the reduced CI grid and `aosuite error` end to end: every row's errors
// are finite, outputs are written, and bad input exits 2 with a message.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "process.hpp"
#include "tuned_presets.hpp"

namespace aosuite::test {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("aosuite_sweep_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The cells of an unquoted CSV line, an empty last cell included.
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells(1);
  for (const char c : line) {
    if (c == ',') {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
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
  const auto flip_at = std::find(header.begin(), header.end(), "frame_flip") - header.begin();
  ASSERT_LT(std::size_t(flip_at), header.size()) << "no frame_flip column";
  int rows = 0;
  for (; std::getline(csv, line); ++rows) {
    const std::vector<std::string> cells = split(line);
    ASSERT_EQ(cells.size(), header.size()) << line;
    // The final image's FLIP against the reference-shaded frame: some error, never all.
    const double frame_flip = std::strtod(cells[std::size_t(flip_at)].c_str(), nullptr);
    EXPECT_GT(frame_flip, 0.0) << line;
    EXPECT_LT(frame_flip, 1.0) << line;
    for (std::size_t i = 8; i < cells.size(); ++i) {  // times and errors
      if (header[i] == "params") continue;
      const double v = std::strtod(cells[i].c_str(), nullptr);
      EXPECT_TRUE(std::isfinite(v) && !cells[i].empty()) << header[i] << " in " << line;
    }
  }
  // four techniques x 2 samples x 2 radii and GTAO x 2 radii, two views
  EXPECT_EQ(rows, (4 * 4 + 2) * 2);
  const auto j = nlohmann::json::parse(std::ifstream(dir / "out" / "sweep.json"));
  EXPECT_EQ(j["fit_on_one_view"].size(), 5u);
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
  EXPECT_EQ(rows, (4 * 4 + 2) * 2);  // the plane's two views
  // The last line names every file written, the plot included, not only the CSV.
  EXPECT_NE(o.out.find("36 rows in "), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("sweep.csv"), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("sweep_64x36.svg"), std::string::npos) << o.out;
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
  EXPECT_GT(j["frame"]["flip"].get<double>(), 0.0);
  EXPECT_LT(j["frame"]["flip"].get<double>(), 1.0);
  EXPECT_GT(j["frame"]["ssim"].get<double>(), 0.0);
  EXPECT_LT(j["frame"]["ssim"].get<double>(), 1.0);
  const std::string stem =
      j["scene"].get<std::string>() + "_" + j["view"].get<std::string>() + "_sao_";
  for (const char* f : {"reference.exr", "reference.png", "ao.png", "error.png"})
    EXPECT_TRUE(fs::exists(dir / "out" / (stem + f))) << f;
  // The EXR (written through libaosuite_exr.so) holds the float reference the PNG shows.
  auto read = [&](const std::string& f, OIIO::TypeDesc type, std::vector<float>& px) {
    auto in = OIIO::ImageInput::open((dir / "out" / (stem + f)).string());
    ASSERT_TRUE(in) << f << ": " << OIIO::geterror();
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.width, 96);
    EXPECT_EQ(spec.height, 54);
    px.resize(std::size_t(spec.width) * std::size_t(spec.height));
    ASSERT_TRUE(in->read_image(
        0, 0, 0, 1, type == OIIO::TypeDesc::UINT8 ? OIIO::TypeDesc::FLOAT : type, px.data()));
  };
  std::vector<float> exr, png;
  read("reference.exr", OIIO::TypeDesc::FLOAT, exr);
  read("reference.png", OIIO::TypeDesc::UINT8, png);  // as 0..1
  ASSERT_EQ(exr.size(), png.size());
  for (std::size_t i = 0; i < exr.size(); ++i) {
    ASSERT_NEAR(exr[i], png[i], 0.5 / 255 + 1e-6) << "pixel " << i;
  }
}

// `--pipeline` reaches error's and sweep's renders: the compute pipeline measures the same
// error as the fragment one (the same AO on llvmpipe, compute_pipeline_tests), and both say
// which ran (sweep.json too: shards of different pipelines do not merge).
TEST(SweepCli, ErrorAndSweepTakeThePipeline) {
  const fs::path dir = scratch("pipeline");
  nlohmann::json errors[2];
  const char* pipelines[] = {"fragment", "compute"};
  for (int i = 0; i < 2; ++i) {
    const Outcome o =
        run_shell(command(dir,
                          "error --scene corner --technique gtao --width 48 --height 27 --rays 16 "
                          "--json --pipeline " +
                              std::string(pipelines[i])),
                  dir);
    ASSERT_EQ(o.rc, 0) << o.err;
    const auto j = nlohmann::json::parse(o.out);
    EXPECT_EQ(j["pipeline"], pipelines[i]);
    errors[i] = j["error"];
  }
  EXPECT_EQ(errors[0], errors[1]);
  const Outcome o =
      run_shell(command(dir, "sweep " + std::string(AOSUITE_SOURCE_DIR) +
                                 "/suites/sweep_ci.toml --scene plane --resolution 32x18 "
                                 "--pipeline compute --out " +
                                 (dir / "out").string()),
                dir);
  ASSERT_EQ(o.rc, 0) << o.err;
  const auto j = nlohmann::json::parse(std::ifstream(dir / "out" / "sweep.json"));
  EXPECT_EQ(j["pipeline"], "compute");  // what its times are of
}

// Fixed parameters reach every configuration of their technique and the outputs name them.
TEST(SweepCli, FixedParamsApplyToTheirTechnique) {
  const fs::path dir = scratch("params");
  const std::string grid =
      "scenes = [\"village\"]\nviews = [\"street\"]\nresolutions = [[160, 90]]\n"
      "runs = 1\nrays = 16\nunbounded = false\n"
      "[techniques.mssao]\nsamples = [8]\nradius = [2]\n";
  std::ofstream(dir / "plain.toml") << grid;
  std::ofstream(dir / "fine_only.toml")
      << grid << "params = { level_weights = [1, 0, 0, 0, 0], blur = \"none\" }\n";
  auto run = [&](const std::string& name) {
    const Outcome o = run_shell(command(dir, "sweep " + (dir / (name + ".toml")).string() +
                                                 " --out " + (dir / name).string()),
                                dir);
    EXPECT_EQ(o.rc, 0) << o.err;
    const auto j = nlohmann::json::parse(std::ifstream(dir / name / "sweep.json"));
    EXPECT_EQ(j["rows"].size(), 1u);
    return j["rows"][0];
  };
  const auto plain = run("plain"), fine = run("fine_only");
  EXPECT_TRUE(plain["params"].empty());
  EXPECT_EQ(fine["params"]["level_weights"], "1,0,0,0,0");
  EXPECT_EQ(fine["params"]["blur"], "none");
  EXPECT_NE(plain["error"]["all"]["rmse"], fine["error"]["all"]["rmse"]);
  std::ifstream csv(dir / "fine_only" / "sweep.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_TRUE(header.ends_with(",params")) << header;
  EXPECT_TRUE(row.ends_with(",\"blur=none level_weights=1,0,0,0,0\"")) << row;
}

// A technique's preset (a file beside the grid, or a built-in name): its values under the
// table's params, its intensity where the grid has no intensity axis, never its radius.
TEST(SweepCli, APresetAppliesUnderTheTablesParams) {
  const fs::path dir = scratch("preset");
  std::ofstream(dir / "p.toml") << "technique = \"gtao\"\n[params]\nslices = 2\nsteps = 5\n"
                                   "intensity = 1.25\nradius = 7\n";
  std::ofstream(dir / "grid.toml")
      << "scenes = [\"corner\"]\nviews = [\"inside\"]\nresolutions = [[64, 36]]\n"
         "runs = 1\nrays = 16\nunbounded = false\n"
         "[techniques.gtao]\nradius = [0.5]\npreset = \"p.toml\"\nparams = { steps = 4 }\n"
         "[techniques.sao]\nradius = [0.5]\npreset = \"tuned\"\n";
  const Outcome o = run_shell(
      command(dir, "sweep " + (dir / "grid.toml").string() + " --out " + (dir / "out").string()),
      dir);
  ASSERT_EQ(o.rc, 0) << o.err;
  const auto rows = nlohmann::json::parse(std::ifstream(dir / "out" / "sweep.json"))["rows"];
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["params"]["slices"], "2");  // the preset's
  EXPECT_EQ(rows[0]["params"]["steps"], "4");   // the table's params win
  EXPECT_EQ(rows[0]["intensity"], 1.25);        // no intensity axis: the preset's
  EXPECT_EQ(rows[0]["radius"], 0.5);            // the axis, never the preset's
  EXPECT_TRUE(rows[1]["params"].contains("radius_scale")) << rows[1];
  std::ofstream(dir / "bad.toml") << "scenes = [\"corner\"]\nresolutions = [[64, 36]]\n"
                                     "[techniques.sao]\nradius = [0.5]\npreset = \"p.toml\"\n";
  const Outcome bad = run_shell(
      command(dir, "sweep " + (dir / "bad.toml").string() + " --out " + (dir / "b").string()), dir);
  EXPECT_EQ(bad.rc, 2);
  EXPECT_NE(bad.err.find("a preset for gtao, not sao"), std::string::npos) << bad.err;
  // `sweep --preset` gives every table without its own preset one, samples included.
  std::ofstream(dir / "plain.toml")
      << "scenes = [\"corner\"]\nviews = [\"inside\"]\n"
         "resolutions = [[64, 36]]\nruns = 1\nrays = 16\n"
         "unbounded = false\n[techniques.ue4]\nradius = [0.5]\n"
         "[techniques.pmi]\nradius = [0.5]\n"
         "params = { viewpoints = 12, pmi_resolution = 64, contrast = 2 }\n";
  const Outcome tuned = run_shell(command(dir, "sweep " + (dir / "plain.toml").string() +
                                                   " --preset tuned --out " + (dir / "t").string()),
                                  dir);
  ASSERT_EQ(tuned.rc, 0) << tuned.err;
  const auto tuned_rows = nlohmann::json::parse(std::ifstream(dir / "t" / "sweep.json"))["rows"];
  ASSERT_EQ(tuned_rows.size(), 2u);
  for (const auto& row : tuned_rows) {
    if (row["technique"] == "ue4") {
      EXPECT_TRUE(row["params"].contains("radius_scale")) << row;
      // Every value of the built-in preset, its samples among them, as the row records it.
      for (const auto& [key, value] : test::tuned_params("ue4")) {
        if (key == "samples") {
          EXPECT_EQ(row["samples"], value) << row;
        } else if (row["params"].contains(key)) {
          EXPECT_NEAR(std::stod(row["params"][key].get<std::string>()), value.get<double>(), 1e-6)
              << key << " " << row;
        }
      }
    } else {  // PMI's tuned preset keeps the paper's map (its tune found no held-out gain)
      EXPECT_EQ(row["technique"], "pmi");
      EXPECT_EQ(row["params"]["contrast"], "2") << "the table's params win over the preset's";
    }
  }
}

// A grid split over shards and merged is the single run: the same rows in the same order with
// the same errors and fit (times are measured again, so they are left out of the comparison).
TEST(SweepCli, ShardsMergeIntoTheSingleRun) {
  const fs::path dir = scratch("shards");
  const std::string grid = std::string(AOSUITE_SOURCE_DIR) + "/suites/sweep_ci.toml";
  auto sweep = [&](const std::string& args) {
    return run_shell(command(dir, "sweep " + args), dir);
  };
  ASSERT_EQ(sweep(grid + " --out " + (dir / "one").string()).rc, 0);
  for (int i = 0; i < 3; ++i) {
    const std::string shard = std::to_string(i) + "/3";
    ASSERT_EQ(
        sweep(grid + " --shard " + shard + " --out " + (dir / shard.substr(0, 1)).string()).rc, 0);
  }
  const std::string shards =
      " --merge " + (dir / "0").string() + " --merge " + (dir / "1").string() + " --merge ";
  const Outcome merged = sweep(shards + (dir / "2").string() + " --out " + (dir / "all").string());
  ASSERT_EQ(merged.rc, 0) << merged.err;
  auto load = [](const fs::path& p) {
    nlohmann::json j = nlohmann::json::parse(std::ifstream(p / "sweep.json"));
    for (nlohmann::json& r : j["rows"]) r.erase("ao_gl_ms");
    return j;
  };
  const nlohmann::json one = load(dir / "one"), all = load(dir / "all");
  EXPECT_EQ(all["rows"], one["rows"]);
  EXPECT_EQ(all["fit_on_one_view"], one["fit_on_one_view"]);
  EXPECT_EQ(all["configurations"], one["configurations"]);
  EXPECT_FALSE(all.contains("shard"));
  EXPECT_TRUE(fs::exists(dir / "all" / "sweep_160x90.svg"));
  // A shard missing, or one merged twice, is refused and writes nothing.
  for (const std::string& bad :
       {shards + (dir / "1").string(), " --merge " + (dir / "0").string()}) {
    const Outcome o = sweep(bad + " --out " + (dir / "bad").string());
    EXPECT_EQ(o.rc, 2) << bad;
    EXPECT_FALSE(fs::exists(dir / "bad")) << bad;
  }
}

TEST(SweepCli, BadInputExitsTwo) {
  const fs::path dir = scratch("bad");
  std::ofstream(dir / "bad.toml") << "scenes = [\"village\"]\nresolutions = [[160, 90]]\n"
                                     "[techniques.blurry]\nsamples = [1]\nradius = [1]\n";
  Outcome o = run_shell(command(dir, "sweep " + (dir / "bad.toml").string()), dir);
  EXPECT_EQ(o.rc, 2);
  EXPECT_NE(o.err.find("bad.toml"), std::string::npos) << o.err;
  // fixed parameters: an axis, an unknown key, a value of the wrong kind
  for (const char* params : {"{ samples = 4 }", "{ colour = 1 }", "{ blur = \"sharp\" }"}) {
    std::ofstream(dir / "bad_params.toml")
        << "scenes = [\"village\"]\nresolutions = [[160, 90]]\n[techniques.sao]\nsamples = "
           "[1]\nradius = [1]\nparams = "
        << params << "\n";
    o = run_shell(command(dir, "sweep " + (dir / "bad_params.toml").string()), dir);
    EXPECT_EQ(o.rc, 2) << params;
    EXPECT_NE(o.err.find("techniques.sao.params"), std::string::npos) << o.err;
  }
  // A sample count for a technique that takes none (GTAO) would label rows with a value no
  // pass read.
  std::ofstream(dir / "gtao.toml") << "scenes = [\"village\"]\nresolutions = [[160, 90]]\n"
                                      "[techniques.gtao]\nsamples = [4]\nradius = [1]\n";
  o = run_shell(command(dir, "sweep " + (dir / "gtao.toml").string()), dir);
  EXPECT_EQ(o.rc, 2);
  EXPECT_NE(o.err.find("gtao takes no sample count"), std::string::npos) << o.err;
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

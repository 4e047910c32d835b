// The GL backends through the CLI, as a user picks them: EGL (the default) and OSMesa render
// the same bytes, gl-info lists what exists, bad choices are refused in one line with nothing
// written, and per-pass GPU times add up within the frame's wall time. (A build without
// OSMesa is tested by tests/no_osmesa_build.sh.)
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "png_fixture.hpp"
#include "process.hpp"

namespace aosuite {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kBin = AOSUITE_BIN;
const std::string kSource = AOSUITE_SOURCE_DIR;

std::string read_bytes(const fs::path& p) {
  std::stringstream s;
  s << std::ifstream(p, std::ios::binary).rdbuf();
  return s.str();
}

json gl_info(const test::TempDir& dir) {
  const test::Outcome o = test::run_shell(kBin + " gl-info --json", dir.path());
  EXPECT_EQ(o.rc, 0) << o.err;
  return json::parse(o.out);
}

int count_lines(const std::string& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

TEST(GlBackend, GlInfoListsAUsableEglDeviceAndWhatTheCommandsRenderWith) {
  const test::TempDir dir;
  const json info = gl_info(dir);
  bool usable_egl_device = false;
  for (const json& b : info["backends"]) {
    if (b["backend"] == "egl" && b["device"].get<int>() >= 0 && b["meets_requirement"]) {
      usable_egl_device = true;
      EXPECT_FALSE(b["renderer"].get<std::string>().empty());
      EXPECT_EQ(b["error"], "");
    }
  }
  EXPECT_TRUE(usable_egl_device) << info.dump(2);
  // `auto` renders through EGL's devices, a GPU first: never OSMesa while a device works.
  const std::string selected = info["selected"];
  EXPECT_EQ(selected.rfind("EGL device ", 0), 0u) << selected;
  const test::Outcome text = test::run_shell(kBin + " gl-info", dir.path());
  EXPECT_EQ(text.rc, 0);
  EXPECT_NE(text.out.find("renders with: " + selected), std::string::npos) << text.out;
  // llvmpipe keeps the fragment pipeline by default (bench/README.md, issue 44).
  EXPECT_EQ(info["pipeline"], "fragment");
  EXPECT_NE(text.out.find("pipeline: fragment"), std::string::npos) << text.out;
}

TEST(GlBackend, EglAndOsMesaRenderEveryDefaultSuiteCaseToTheSameBytes) {
  const test::TempDir dir;
  if (!gl_info(dir)["osmesa_built"]) GTEST_SKIP() << "this build has no OSMesa backend";
  auto check = [&](const std::string& backend, int jobs) {
    const test::Outcome o = test::run_shell(
        kBin + " check " + kSource + "/suites/default.toml --no-reuse --gl " + backend +
            " --jobs " + std::to_string(jobs) + " --report " + (dir / backend).string(),
        dir.path());
    EXPECT_EQ(o.rc, 0) << backend << ": " << o.err << o.out;
  };
  check("egl", 2);  // one context per thread
  check("osmesa", 1);
  int images = 0;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir / "egl" / "cases")) {
    if (e.path().extension() != ".png") continue;
    const fs::path twin = dir / "osmesa" / fs::relative(e.path(), dir / "egl");
    ASSERT_TRUE(fs::exists(twin)) << twin;
    EXPECT_EQ(read_bytes(e.path()), read_bytes(twin)) << e.path();
    ++images;
  }
  EXPECT_GE(images, 3 * 42);  // no_ao, with_ao and ao_only of every case
}

TEST(GlBackend, BadChoicesExitTwoInOneLineAndWriteNothing) {
  const test::TempDir dir;
  const std::string render = " render --width 8 --height 8 --out " + (dir / "out").string();
  struct Bad {
    std::string command, says;
  };
  for (const Bad& bad : {
           Bad{kBin + render + " --gl-device 1000", "EGL device 1000 does not exist"},
           Bad{"AOSUITE_GL_DEVICE=999 " + kBin + render, "EGL device 999 does not exist"},
           Bad{"AOSUITE_GL_DEVICE=x " + kBin + render, "AOSUITE_GL_DEVICE: 'x'"},
           Bad{"AOSUITE_GL=vulkan " + kBin + render, "unknown GL backend 'vulkan'"},
           Bad{kBin + render + " --gl vulkan", "aosuite render: --gl: vulkan not in"},
           Bad{kBin + render + " --pipeline vertex", "unknown pipeline 'vertex'"},
           Bad{kBin + render + " --gl osmesa --gl-device 0", "OSMesa has none"},
           // No EGL driver at all (GLVND finds no vendor library), and one below OpenGL 4.5.
           Bad{"__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json " + kBin + render + " --gl egl",
               "no EGL driver found"},
           Bad{"MESA_GL_VERSION_OVERRIDE=3.3 " + kBin + render + " --gl egl",
               "no OpenGL 4.5 core context"},
       }) {
    const test::Outcome o = test::run_shell(bad.command, dir.path());
    EXPECT_EQ(o.rc, 2) << bad.command;
    EXPECT_EQ(count_lines(o.err), 1) << bad.command << ": " << o.err;
    EXPECT_NE(o.err.find(bad.says), std::string::npos) << bad.command << ": " << o.err;
    EXPECT_FALSE(fs::exists(dir / "out")) << bad.command;
  }
  // The device list in the message names the devices that do exist.
  const test::Outcome o = test::run_shell(kBin + render + " --gl-device 1000", dir.path());
  EXPECT_NE(o.err.find("EGL device 0 ("), std::string::npos) << o.err;
}

// In both pipelines (the compute one's passes have the same names, so pass tables line up).
TEST(GlBackend, PassTimesAreEachPositiveAndAddUpWithinTheFrame) {
  for (const std::string pipeline : {"fragment", "compute"}) {
    const test::TempDir dir;
    const test::Outcome o = test::run_shell(
        kBin +
            " render --scene village --technique sao --width 320 --height 180 --runs 1 "
            "--outputs all --pipeline " +
            pipeline + " --out " + dir.path().string(),
        dir.path());
    ASSERT_EQ(o.rc, 0) << o.err;
    const json j = json::parse(read_bytes(dir / "village_street_sao.json"));
    EXPECT_EQ(j["pipeline"], pipeline);
    EXPECT_EQ(j["gl_device"].get<std::string>().rfind("EGL", 0), 0u) << j["gl_device"];
    const double frame = j["median_ms"]["frame_wall"];
    double sum = 0;
    for (const std::string pass : {"gbuffer", "sao_pyramid", "ao", "blur", "blend"}) {
      ASSERT_TRUE(j["median_ms"].contains(pass)) << pass;
      EXPECT_GT(j["median_ms"][pass].get<double>(), 0) << pass;
      sum += j["median_ms"][pass].get<double>();
    }
    // Passes run one after another, so their GPU times cannot add up to more than the wall
    // time around them (10 % and 1 ms for clock granularity). One timed frame, so every figure
    // is of the same frame: medians of several would each come from another.
    EXPECT_LE(sum, frame * 1.1 + 1.0) << pipeline << " " << j["median_ms"].dump();
    EXPECT_GT(frame, 0);
  }
}

}  // namespace
}  // namespace aosuite

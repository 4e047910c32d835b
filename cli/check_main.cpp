// Entry point of libaosuite_check.so: `check`, `bless`, `report` and `tolerances`, the harness on
// the command line. It holds no renderer: a suite of files and commands (and folder mode) maps no
// GL, Embree, assimp or OpenCV. Only a suite or report with scene cases loads libaosuite_gl.so,
// which registers the AO bench's case kind (ao/scene_cases.hpp).
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "cli/commands.hpp"
#include "cli/usage_error.hpp"
#include "harness/case_kind.hpp"
#include "harness/invocation.hpp"

namespace {

namespace fs = std::filesystem;

// Opens libaosuite_gl.so beside this library and lets it register its kinds. It links this
// library (cli/CMakeLists.txt) rather than a copy of the harness, so it registers into this
// registry of kinds.
void load_ao_bench() {
  Dl_info self{};
  if (!dladdr(reinterpret_cast<const void*>(&load_ao_bench), &self) || !self.dli_fname)
    throw std::runtime_error("cannot find libaosuite_check.so's own path");
  const fs::path gl = fs::path(self.dli_fname).parent_path() / "libaosuite_gl.so";
  if (!fs::exists(gl)) {
    throw std::runtime_error(
        "scene cases need the AO bench (libaosuite_gl.so), which this aosuite was built without");
  }
  void* handle = dlopen(gl.c_str(), RTLD_NOW | RTLD_LOCAL);
  auto* entry =
      handle ? reinterpret_cast<void (*)()>(dlsym(handle, "aosuite_register_kinds")) : nullptr;
  if (!entry) throw std::runtime_error(std::string("cannot load the AO bench: ") + dlerror());
  entry();
}

// --gl and --gl-device choose the renderer's context for scene cases (they set AOSUITE_GL and
// AOSUITE_GL_DEVICE, which the renderer reads when it makes one).
void add_gl_options(CLI::App& app) {
  for (const char* name : {"check", "bless"}) {
    CLI::App* cmd = app.get_subcommand(name);
    cmd->add_option_function<std::string>(
           "--gl", [](const std::string& v) { setenv("AOSUITE_GL", v.c_str(), 1); },
           "scene cases: OpenGL backend auto (EGL, else OSMesa), egl, osmesa; default "
           "$AOSUITE_GL or auto")
        ->check(CLI::IsMember({"auto", "egl", "osmesa"}))
        ->option_text("BACKEND");
    cmd->add_option_function<int>(
           "--gl-device",
           [](int index) { setenv("AOSUITE_GL_DEVICE", std::to_string(index).c_str(), 1); },
           "scene cases: EGL device index (aosuite gl-info lists them); default "
           "$AOSUITE_GL_DEVICE or the first GPU, else Mesa's software device")
        ->check(CLI::Range(0, 1024))
        ->option_text("INDEX");
  }
}

}  // namespace

extern "C" int aosuite_check_main(int argc, char** argv) {
  aosuite::harness::set_invoked_as(argv[0]);  // for the commands it prints
  aosuite::harness::set_kind_loader(load_ao_bench);
  CLI::App app{"aosuite: suites, goldens and reports"};
  app.require_subcommand(1);
  int rc = aosuite::cli::kExitSame;
  aosuite::cli::add_check_command(app, rc);
  aosuite::cli::add_bless_command(app, rc);
  aosuite::cli::add_report_command(app, rc);
  aosuite::cli::add_tolerances_command(app, rc);
  add_gl_options(app);
  return aosuite::cli::run_library_app(app, argc, argv, rc);
}

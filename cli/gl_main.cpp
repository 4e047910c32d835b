// Entry point of libaosuite_gl.so, which `aosuite` loads only for the commands that need
// OpenGL: Mesa and LLVM cost tens of milliseconds of start-up that `aosuite compare` must not
// pay (OpenImageIO, ~360 ms, is loaded later still: only to write an EXR). Each command here
// is also listed in main.cpp's kLibraryCommands.
#include "ao/scene_cases.hpp"
#include "cli/commands.hpp"
#include "cli/usage_error.hpp"
#include "harness/invocation.hpp"
#include "renderer/gl/gl_context.hpp"

namespace {

// Every GL command takes the same two flags; they override AOSUITE_GL and AOSUITE_GL_DEVICE.
void add_gl_options(CLI::App& app) {
  namespace rd = aosuite::renderer;
  for (CLI::App* cmd : app.get_subcommands({})) {
    cmd->add_option_function<std::string>(
           "--gl", [](const std::string& name) { rd::set_gl_backend(rd::parse_gl_backend(name)); },
           "OpenGL backend: auto (EGL, else OSMesa), egl, osmesa; default $AOSUITE_GL or auto")
        ->check(CLI::IsMember({"auto", "egl", "osmesa"}))
        ->option_text("BACKEND");
    cmd->add_option_function<int>(
           "--gl-device", [](int index) { rd::set_gl_device(index); },
           "EGL device index (aosuite gl-info lists them); default $AOSUITE_GL_DEVICE or the "
           "first GPU, else Mesa's software device")
        ->check(CLI::Range(0, 1024))
        ->option_text("INDEX");
  }
}

}  // namespace

extern "C" int aosuite_gl_main(int argc, char** argv) {
  aosuite::harness::set_invoked_as(argv[0]);  // for the commands it prints
  CLI::App app{"aosuite: rendering commands"};
  app.require_subcommand(1);
  int rc = aosuite::cli::kExitSame;
  aosuite::cli::add_render_command(app, rc);
  aosuite::cli::add_scenes_command(app, rc);
  aosuite::cli::add_viewpoints_command(app, rc);
  aosuite::cli::add_pmi_study_command(app, rc);
  aosuite::cli::add_error_command(app, rc);
  aosuite::cli::add_sweep_command(app, rc);
  aosuite::cli::add_gl_info_command(app, rc);
  aosuite::cli::add_tune_command(app, rc);
  add_gl_options(app);
  return aosuite::cli::run_library_app(app, argc, argv, rc);
}

// Called by libaosuite_check.so when a suite or report holds scene cases.
extern "C" void aosuite_register_kinds() { aosuite::ao::register_scene_cases(); }

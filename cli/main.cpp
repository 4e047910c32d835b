// aosuite: a thin command line over the library; each subcommand lives in its own file.
#include <fmt/format.h>

#include <array>
#include <csignal>
#include <cstring>
#include <exception>
#include <string>

#include "cli/commands.hpp"
#include "cli/usage_error.hpp"
#include "common/huge_page_malloc.hpp"
#include "common/sibling_library.hpp"

namespace {

// Commands that need OpenGL live in libaosuite_gl.so beside this binary (cli/gl_main.cpp),
// loaded on demand, so that `aosuite compare` starts without loading Mesa, LLVM or
// OpenImageIO. Listed here for dispatch and for --help.
struct GlCommand {
  const char* name;
  const char* help;
};
constexpr std::array kGlCommands{
    GlCommand{"render", "Render a scene view with one AO technique"},
    GlCommand{"scenes", "List built-in scenes and their views, or check scene files"},
    GlCommand{"check", "Render a suite and gate each case against its golden (see check --help)"},
    GlCommand{"bless", "Accept current renders of a suite as its goldens"},
    GlCommand{"report", "Merge shard reports (report merge --out DIR SHARD...)"},
    GlCommand{"viewpoints", "PMI viewpoint selection: best/worst views, VMI and PMI(v) per view"},
    GlCommand{"pmi-study", "PMI resolution x viewpoints study: time, agreement with ray tracing"},
    GlCommand{"error", "Measure a technique's AO against a ray-traced reference"},
    GlCommand{"sweep",
              "Time and error of each technique over a samples x radius x resolution grid"},
    GlCommand{"gl-info", "List the OpenGL backends and devices this machine can render with"},
};

bool is_gl_command(const char* name) {
  for (const GlCommand& c : kGlCommands) {
    if (std::strcmp(name, c.name) == 0) return true;
  }
  return false;
}

int run_gl_command(int argc, char** argv) {
  aosuite::reexec_with_huge_page_malloc(argv);  // see there: ~20 % off a render process
  std::string error;
  auto* entry =
      aosuite::sibling_symbol<int(int, char**)>("libaosuite_gl.so", "aosuite_gl_main", error);
  if (!entry) {
    fmt::print(stderr, "aosuite: cannot load the OpenGL commands: {}\n", error);
    return aosuite::cli::kExitError;
  }
  return entry(argc, argv);
}

std::string command_list() {
  std::string out = "compare";
  for (const GlCommand& c : kGlCommands) out += std::string(", ") + c.name;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  // A write over the file size limit (ulimit -f) fails with EFBIG and a message naming the file,
  // instead of the signal ending the process without a word.
  std::signal(SIGXFSZ, SIG_IGN);
  if (argc > 1 && is_gl_command(argv[1])) return run_gl_command(argc, argv);
  if (argc > 1 && argv[1][0] != '-' && std::strcmp(argv[1], "compare") != 0) {
    return aosuite::cli::usage_error(
        nullptr, fmt::format("unknown command '{}' (commands: {}; aosuite --help)", argv[1],
                             command_list()));
  }
  CLI::App app{"aosuite: ambient-occlusion rendering and perceptual image regression suite"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "aosuite 0.1.0");
  int rc = aosuite::cli::kExitSame;
  aosuite::cli::add_compare_command(app, rc);
  // Listed for --help; run_gl_command handles them before parsing.
  for (const GlCommand& c : kGlCommands) app.add_subcommand(c.name, c.help)->allow_extras();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    if (argc < 2) {
      return aosuite::cli::usage_error(
          nullptr, fmt::format("a command is required ({}; aosuite --help)", command_list()));
    }
    const bool compare = std::strcmp(argv[1], "compare") == 0;
    return aosuite::cli::usage_error(compare ? "compare" : nullptr, e.what());
  } catch (const std::exception& e) {
    fmt::print(stderr, "aosuite: {}\n", e.what());
    return aosuite::cli::kExitError;
  }
  return rc;
}

// aosuite: a thin command line over the library; each subcommand lives in its own file.
#include <fmt/format.h>

#include <array>
#include <csignal>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>

#include "cli/commands.hpp"
#include "cli/usage_error.hpp"
#include "common/huge_page_malloc.hpp"
#include "common/sibling_library.hpp"

namespace {

// Every command but compare lives in a library beside this binary, loaded on demand, so that
// `aosuite compare` starts without loading them: the harness (libaosuite_check.so, no GL) and
// the AO bench (libaosuite_gl.so: Mesa, LLVM, Embree, assimp). Listed here for dispatch and
// for --help.
struct LibraryCommand {
  const char* name;
  const char* help;
  const char* library;
};
constexpr const char* kHarness = "libaosuite_check.so";
constexpr const char* kBench = "libaosuite_gl.so";
constexpr std::array kLibraryCommands{
    LibraryCommand{"check", "Gate a suite's or a folder's images against goldens (check --help)",
                   kHarness},
    LibraryCommand{"bless", "Accept a suite's or a folder's current images as its goldens",
                   kHarness},
    LibraryCommand{"report", "Merge shard reports (report merge --out DIR SHARD...)", kHarness},
    LibraryCommand{"tolerances",
                   "Suggest each case's tolerance from repeated runs, with a margin a held-back "
                   "run needed (tolerances suggest SUITE --report DIR...)",
                   kHarness},
    LibraryCommand{"render", "Render a scene view with one AO technique", kBench},
    LibraryCommand{"scenes", "List built-in scenes and their views, or check scene files", kBench},
    LibraryCommand{"viewpoints",
                   "PMI viewpoint selection: best/worst views, VMI and PMI(v) per view", kBench},
    LibraryCommand{"pmi-study",
                   "PMI resolution x viewpoints study: time, agreement with ray tracing", kBench},
    LibraryCommand{"error", "Measure a technique's AO against a ray-traced reference", kBench},
    LibraryCommand{"sweep",
                   "Time and error of each technique over a samples x radius x resolution grid",
                   kBench},
    LibraryCommand{"tune",
                   "Search a technique's parameters against the ray-traced reference (a preset)",
                   kBench},
    LibraryCommand{"gl-info", "List the OpenGL backends and devices this machine can render with",
                   kBench},
};

const LibraryCommand* library_command(const char* name) {
  for (const LibraryCommand& c : kLibraryCommands) {
    if (std::strcmp(name, c.name) == 0) return &c;
  }
  return nullptr;
}

int run_library_command(const LibraryCommand& command, int argc, char** argv) {
  aosuite::reexec_with_huge_page_malloc(argv);  // see there: ~20 % off a render process
  const bool harness = command.library == kHarness;
  std::string error;
  auto* entry = aosuite::sibling_symbol<int(int, char**)>(
      command.library, harness ? "aosuite_check_main" : "aosuite_gl_main", error);
  if (!entry && !harness &&
      !std::filesystem::exists(aosuite::sibling_library_path(command.library))) {
    fmt::print(stderr,
               "aosuite {}: this aosuite was built without the AO bench (-DAOSUITE_RENDERER=OFF); "
               "compare, check, bless and report work on images\n",
               command.name);
    return aosuite::cli::kExitError;
  }
  if (!entry) {
    fmt::print(stderr, "aosuite: cannot load the {} command: {}\n", command.name, error);
    return aosuite::cli::kExitError;
  }
  return entry(argc, argv);
}

std::string command_list() {
  std::string out = "compare";
  for (const LibraryCommand& c : kLibraryCommands) out += std::string(", ") + c.name;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  // A write over the file size limit (ulimit -f) fails with EFBIG and a message naming the file,
  // instead of the signal ending the process without a word.
  std::signal(SIGXFSZ, SIG_IGN);
  // A reader that has gone (`aosuite bless | head -1`) must not end a bless half way through
  // its cases: writes to the pipe fail with EPIPE instead, and check and bless go on.
  std::signal(SIGPIPE, SIG_IGN);
  if (argc > 1) {
    if (const LibraryCommand* c = library_command(argv[1]))
      return run_library_command(*c, argc, argv);
  }
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
  // Listed for --help; run_library_command handles them before parsing.
  for (const LibraryCommand& c : kLibraryCommands)
    app.add_subcommand(c.name, c.help)->allow_extras();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    if (argc < 2) {
      return aosuite::cli::usage_error(
          nullptr, fmt::format("a command is required ({}; aosuite --help)", command_list()));
    }
    const char* command = std::strcmp(argv[1], "compare") == 0 ? "compare" : nullptr;
    if (dynamic_cast<const CLI::ExtrasError*>(&e))
      return aosuite::cli::usage_error(command, aosuite::cli::extras_problem(app, command));
    return aosuite::cli::usage_error(command, e.what());
  } catch (const std::exception& e) {
    fmt::print(stderr, "aosuite: {}\n", e.what());
    return aosuite::cli::kExitError;
  }
  return rc;
}

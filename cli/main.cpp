// aosuite: a thin command line over the library; each subcommand lives in its own file.
#include <fmt/format.h>

#include <exception>

#include "cli/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"aosuite: ambient-occlusion rendering and perceptual image regression suite"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "aosuite 0.1.0");
  int rc = aosuite::cli::kExitSame;
  aosuite::cli::add_compare_command(app, rc);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : aosuite::cli::kExitError;
  } catch (const std::exception& e) {
    fmt::print(stderr, "aosuite: {}\n", e.what());
    return aosuite::cli::kExitError;
  }
  return rc;
}

// A usage error as one line, "aosuite <command>: <problem>", as every other error is, and the
// exit code for it. Shared by the launcher (main.cpp) and the command libraries (check_main.cpp,
// gl_main.cpp).
#pragma once

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <string>

#include "cli/commands.hpp"

namespace aosuite::cli {

inline int usage_error(const char* command, std::string problem) {
  std::replace(problem.begin(), problem.end(), '\n', ' ');
  while (!problem.empty() && problem.back() == ' ') problem.pop_back();
  fmt::print(stderr, "aosuite{}{}: {}\n", command ? " " : "", command ? command : "", problem);
  return kExitError;
}

// Parses and runs a command library's app (its entry point's body); returns the exit code. The
// launcher has its own C++ runtime (cli/CMakeLists.txt): nothing may unwind into it.
inline int run_library_app(CLI::App& app, int argc, char** argv, const int& rc) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    return usage_error(argc > 1 ? argv[1] : nullptr, e.what());
  } catch (...) {
    std::fputs("aosuite: unexpected error\n", stderr);
    return kExitError;
  }
  return rc;
}

}  // namespace aosuite::cli

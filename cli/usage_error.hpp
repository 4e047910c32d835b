// A usage error as one line, "aosuite <command>: <problem>", as every other error is, and the
// exit code for it. Shared by the launcher (main.cpp) and the GL commands (gl_main.cpp).
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "cli/commands.hpp"

namespace aosuite::cli {

inline int usage_error(const char* command, std::string problem) {
  std::replace(problem.begin(), problem.end(), '\n', ' ');
  while (!problem.empty() && problem.back() == ' ') problem.pop_back();
  fmt::print(stderr, "aosuite{}{}: {}\n", command ? " " : "", command ? command : "", problem);
  return kExitError;
}

}  // namespace aosuite::cli

// A usage error as one line, "aosuite <command>: <problem>", as every other error is, and the
// exit code for it. Shared by the launcher (main.cpp) and the command libraries (check_main.cpp,
// gl_main.cpp).
#pragma once

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "cli/commands.hpp"

namespace aosuite::cli {

inline int usage_error(const char* command, std::string problem) {
  std::replace(problem.begin(), problem.end(), '\n', ' ');
  while (!problem.empty() && problem.back() == ' ') problem.pop_back();
  fmt::print(stderr, "aosuite{}{}: {}\n", command ? " " : "", command ? command : "", problem);
  return kExitError;
}

// Levenshtein distance, for suggesting an option's name.
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// CLI11's "The following arguments were not expected: b a" lists them reversed and suggests
// nothing. This names the first one as the user typed it, and for an option the nearest one the
// command has ("--metrc" -> "--metric"), as git and cargo do.
inline std::string extras_problem(const CLI::App& app, const char* command) {
  const CLI::App* cmd = &app;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    if (command && sub->get_name() == command) cmd = sub;
  const std::vector<std::string> extras = cmd->remaining();
  const std::string help =
      fmt::format("aosuite{}{} --help", command ? " " : "", command ? command : "");
  if (extras.empty()) return fmt::format("unexpected arguments ({})", help);
  const std::string& first = extras.front();
  if (first.size() < 2 || first[0] != '-') {
    return fmt::format("unexpected argument '{}' ({} lists what it takes)", first, help);
  }
  const std::string typed = first.substr(0, first.find('='));
  std::string best;
  std::size_t best_distance = std::string::npos;
  for (const CLI::Option* o : cmd->get_options()) {
    std::vector<std::string> names;
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : o->get_snames()) names.push_back("-" + s);
    for (const std::string& name : names) {
      if (const std::size_t d = edit_distance(typed, name); d < best_distance)
        best_distance = d, best = name;
    }
  }
  // One typo in a short name, about one in three letters in a long one.
  const std::size_t letters = typed.size() - typed.find_first_not_of('-');
  const bool close = letters >= 3 && best_distance <= std::max<std::size_t>(1, letters / 3);
  return fmt::format("unknown option '{}'{} ({} lists them)", typed,
                     close ? fmt::format("; did you mean '{}'?", best) : "", help);
}

// CLI11 names an option's value by its C++ type ("--scene TEXT=village"); an option that does
// not name its own is named after itself here ("--scene SCENE=village").
inline void name_option_values(CLI::App& app) {
  for (CLI::Option* o : app.get_options()) {
    const std::string type = o->get_type_name();
    if (o->get_option_text().empty() && (type == "TEXT" || type == "INT" || type == "UINT" ||
                                         type == "FLOAT" || type == "NUMBER")) {
      std::string name = o->get_single_name();
      std::transform(name.begin(), name.end(), name.begin(),
                     [](char ch) { return ch == '-' ? '_' : std::toupper(ch); });
      o->type_name(name);
    }
  }
  for (CLI::App* sub : app.get_subcommands({})) name_option_values(*sub);
}

// Parses and runs a command library's app (its entry point's body); returns the exit code. The
// launcher has its own C++ runtime (cli/CMakeLists.txt): nothing may unwind into it.
inline int run_library_app(CLI::App& app, int argc, char** argv, const int& rc) {
  name_option_values(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    const char* command = argc > 1 ? argv[1] : nullptr;
    if (dynamic_cast<const CLI::ExtrasError*>(&e))
      return usage_error(command, extras_problem(app, command));
    return usage_error(command, e.what());
  } catch (...) {
    std::fputs("aosuite: unexpected error\n", stderr);
    return kExitError;
  }
  return rc;
}

}  // namespace aosuite::cli

// Each subcommand registers itself on the app and reports its exit code through `rc`.
// Exit codes, for every subcommand: 0 same / passed, 1 different / failed, 2 error.
#pragma once

#include <CLI/CLI.hpp>

namespace aosuite::cli {

inline constexpr int kExitSame = 0;
inline constexpr int kExitDifferent = 1;
inline constexpr int kExitError = 2;

void add_compare_command(CLI::App& app, int& rc);
void add_render_command(CLI::App& app, int& rc);  // in libaosuite_gl.so
void add_scenes_command(CLI::App& app, int& rc);  // in libaosuite_gl.so
void add_check_command(CLI::App& app, int& rc);   // in libaosuite_gl.so
void add_bless_command(CLI::App& app, int& rc);   // in libaosuite_gl.so
void add_report_command(CLI::App& app, int& rc);  // in libaosuite_gl.so

}  // namespace aosuite::cli

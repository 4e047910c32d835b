// Each subcommand registers itself on the app and reports its exit code through `rc`.
// Exit codes, for every subcommand: 0 same / passed, 1 different / failed, 2 error.
#pragma once

#include <fmt/format.h>

#include <CLI/CLI.hpp>

#include "common/printable.hpp"

namespace aosuite::cli {

inline constexpr int kExitSame = 0;
inline constexpr int kExitDifferent = 1;
inline constexpr int kExitError = 2;

// Runs `f` as `cmd`'s action: its return value is the exit code, and any exception becomes
// "aosuite <name>: <reason>" on stderr and exit code 2.
template <typename F>
void guarded(CLI::App* cmd, int& rc, const char* name, F f) {
  cmd->callback([&rc, name, f] {
    try {
      rc = f();
    } catch (const std::exception& e) {
      // Messages may quote files and paths: never raw bytes to the terminal.
      fmt::print(stderr, "aosuite {}: {}\n", name, aosuite::printable(e.what()));
      rc = kExitError;
    }
  });
}

void add_compare_command(CLI::App& app, int& rc);
void add_render_command(CLI::App& app, int& rc);      // in libaosuite_gl.so
void add_scenes_command(CLI::App& app, int& rc);      // in libaosuite_gl.so
void add_check_command(CLI::App& app, int& rc);       // in libaosuite_check.so
void add_bless_command(CLI::App& app, int& rc);       // in libaosuite_check.so
void add_report_command(CLI::App& app, int& rc);      // in libaosuite_check.so
void add_tolerances_command(CLI::App& app, int& rc);  // in libaosuite_check.so
void add_viewpoints_command(CLI::App& app, int& rc);  // in libaosuite_gl.so
void add_pmi_study_command(CLI::App& app, int& rc);   // in libaosuite_gl.so
void add_error_command(CLI::App& app, int& rc);       // in libaosuite_gl.so
void add_sweep_command(CLI::App& app, int& rc);       // in libaosuite_gl.so
void add_gl_info_command(CLI::App& app, int& rc);     // in libaosuite_gl.so
void add_tune_command(CLI::App& app, int& rc);        // in libaosuite_gl.so

}  // namespace aosuite::cli

// Runs an image case's command: argv without a shell, in a given folder, with a time limit.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace aosuite::harness {

struct CommandOutcome {
  int exit_status = -1;  // the exit status; 128 + N when killed by signal N
  int signal = 0;        // N when killed by signal N (else 0, an exit status of 153 included)
  bool timed_out = false;
  std::string stderr_tail;  // the last 4 KiB of what it wrote to stderr
};

// Runs `argv` (argv[0] looked up in PATH when it has no '/') in `cwd` with stdin from
// /dev/null, stdout and stderr into the given files (of which the last 64 KiB are kept, after a
// line giving the full size), and `env` added to this process's environment.
// A command never outlives it: the command runs under a reaper, a forked copy of this process
// that is the child subreaper of the command's whole tree. When the command exits, after
// `timeout_seconds`, or when this process dies, however (PR_SET_PDEATHSIG), the reaper kills
// every descendant, those that called setsid or double-forked included, and reaps them. The
// reaper sits in a process group of its own, so a signal to this process's group, SIGKILL
// included, ends this process and then, through it, the command's tree; the command itself
// also dies with its reaper. Throws std::runtime_error when it cannot be started (naming
// argv[0]).
CommandOutcome run_command(const std::vector<std::string>& argv, const std::filesystem::path& cwd,
                           const std::filesystem::path& stdout_file,
                           const std::filesystem::path& stderr_file, double timeout_seconds,
                           const std::vector<std::string>& env);

}  // namespace aosuite::harness

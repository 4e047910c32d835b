// How this process was started, so the commands it prints (bless hints, the report's approve
// command, a tuned preset's header) run as printed: `aosuite` when it was found on PATH, else
// the path it was started by, made absolute (a printed command may be pasted in another folder).
#pragma once

#include <string>
#include <string_view>

namespace aosuite::harness {

// Records argv[0]; main() calls it once, before any thread starts. Unset (a library user):
// "aosuite".
void set_invoked_as(std::string_view argv0);
// The program for a printed command line, shell-quoted.
std::string program_command();

}  // namespace aosuite::harness

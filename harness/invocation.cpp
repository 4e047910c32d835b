#include "harness/invocation.hpp"

#include <filesystem>
#include <system_error>

#include "harness/escape.hpp"

namespace aosuite::harness {

namespace {
std::string& invoked_as() {
  static std::string program = "aosuite";
  return program;
}
}  // namespace

void set_invoked_as(std::string_view argv0) {
  if (argv0.empty()) return;
  // No slash: the shell found it on PATH, and will again.
  if (argv0.find('/') == std::string_view::npos) {
    invoked_as() = std::string(argv0);
    return;
  }
  std::error_code ec;
  const std::filesystem::path full = std::filesystem::absolute(argv0, ec);
  invoked_as() = ec ? std::string(argv0) : full.lexically_normal().string();
}

std::string program_command() { return shell_quote(invoked_as()); }

}  // namespace aosuite::harness

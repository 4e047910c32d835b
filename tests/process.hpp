// Runs a shell command as a user would and captures its exit status, stdout and stderr.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace aosuite::test {

struct Outcome {
  int rc;
  std::string out, err;
};

// `scratch` receives the captured stderr file.
inline Outcome run_shell(const std::string& command, const std::filesystem::path& scratch) {
  const std::string err_file = (scratch / "stderr.txt").string();
  FILE* p = popen((command + " 2>" + err_file).c_str(), "r");
  std::string out;
  char buf[4096];
  for (std::size_t n; (n = fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  const int status = pclose(p);
  std::stringstream err;
  err << std::ifstream(err_file).rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out, err.str()};
}

// A whole file as text ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& p) {
  std::stringstream s;
  s << std::ifstream(p).rdbuf();
  return s.str();
}

}  // namespace aosuite::test

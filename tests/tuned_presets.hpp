// The built-in tuned presets as the tests read them: ao/presets/tuned-TECHNIQUE.toml's [params],
// so a test follows a re-tune instead of hard-coding its values.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>

#include "process.hpp"

namespace aosuite::test {

// Each value as JSON (a TOML number, list of numbers or quoted word reads the same).
inline std::map<std::string, nlohmann::json> tuned_params(const std::string& technique) {
  std::istringstream file(read_text(std::filesystem::path(AOSUITE_SOURCE_DIR) / "ao" / "presets" /
                                    ("tuned-" + technique + ".toml")));
  std::map<std::string, nlohmann::json> out;
  bool in_params = false;
  for (std::string line; std::getline(file, line);) {
    if (line == "[params]") in_params = true;
    const std::size_t eq = line.find(" = ");
    if (in_params && eq != std::string::npos)
      out[line.substr(0, eq)] = nlohmann::json::parse(line.substr(eq + 3));
  }
  if (out.empty()) throw std::runtime_error("tuned-" + technique + ": no [params]");
  return out;
}

}  // namespace aosuite::test

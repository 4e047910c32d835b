// Reads a suite file (suites/*.toml): the shared keys of every case, image cases (files and
// commands), and the cases of kinds registered from above (harness/case_kind.hpp).
#pragma once

#include <filesystem>

#include "harness/suite.hpp"

namespace aosuite::harness {

// Parses and expands a suite file. Throws std::runtime_error "file:line:col: reason" for
// malformed TOML, unknown keys, wrong types, unknown scenes/views/techniques/parameters,
// impossible sizes and duplicate case ids.
Suite load_suite(const std::filesystem::path& file);

}  // namespace aosuite::harness

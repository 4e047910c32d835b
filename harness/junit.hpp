// JUnit XML for CI systems: one <testcase> per case; failures and errors carry the reason.
#pragma once

#include <filesystem>

#include "harness/results.hpp"

namespace aosuite::harness {

void write_junit(const RunResults& run, const std::filesystem::path& file);

}  // namespace aosuite::harness

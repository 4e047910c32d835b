// JUnit XML for CI systems: one <testcase> per case; failures and errors carry the reason and
// the command that accepts what the report shows, and link the report's panel and the case's
// images (system-out).
#pragma once

#include <filesystem>

#include "harness/results.hpp"

namespace aosuite::harness {

void write_junit(const RunResults& run, const std::filesystem::path& file,
                 const std::filesystem::path& report_dir);

}  // namespace aosuite::harness

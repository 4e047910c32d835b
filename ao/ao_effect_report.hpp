// The AO bench's section of a suite's HTML report: how much AO changes each technique's images
// (the thesis's Tables 11-14) and a link to the latest sweep beside the report.
#pragma once

#include <filesystem>
#include <string>

#include "harness/results.hpp"

namespace aosuite::ao {

std::string ao_effect_section(const harness::RunResults& run,
                              const std::filesystem::path& report_dir);

}  // namespace aosuite::ao

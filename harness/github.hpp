// GitHub Actions' own language for a run (as Filament's renderdiff speaks it): a workflow
// command per case that is not passing (::error or ::warning, shown on the run's page and beside
// the pull request), and a Markdown table for the job's step summary ($GITHUB_STEP_SUMMARY).
// `check` and `report merge` write both when GITHUB_ACTIONS=true.
#pragma once

#include <filesystem>
#include <string>

#include "harness/results.hpp"

namespace aosuite::harness {

// One "::error ...::..." or "::warning ...::..." line per case that failed, is new, could not be
// judged (errors), or passed with a warning or on a retry (warnings); "" when all passed.
std::string github_annotations(const RunResults& run, const std::filesystem::path& report_dir);
// The run's counts, a table of the cases that are not passing (the first 50), the report's
// path and the command that accepts what it shows.
std::string github_step_summary(const RunResults& run, const std::filesystem::path& report_dir);

}  // namespace aosuite::harness

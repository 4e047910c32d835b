// The self-contained HTML page of a run: works from disk, no network, no external scripts;
// every picture is embedded once.
#pragma once

#include <filesystem>

#include "harness/results.hpp"

namespace aosuite::harness {

// Writes `report_dir`/index.html from `run`, embedding the pictures its cases name (paths
// relative to `report_dir`/cases). Throws naming the file if it cannot read or write.
struct ReportOptions {
  bool single_file = false;  // embed every image (base64) instead of linking the files beside
};
void write_html_report(const RunResults& run, const std::filesystem::path& report_dir,
                       const ReportOptions& options = {});

// "123 files, 4.5 MB": what a CI uploads as the report's artifact (links not followed).
std::string report_size(const std::filesystem::path& report_dir);

}  // namespace aosuite::harness

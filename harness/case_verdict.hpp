// Judging a case's images against its goldens (or folder mode's expected files), writing the
// diff images the report shows; and where bless writes each image.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "harness/case_kind.hpp"
#include "harness/results.hpp"
#include "harness/runner.hpp"

namespace aosuite::harness {

// Folder mode reads, writes and removes under --expected by relative path: never through a link
// there (a linked file or folder leads out of --expected). Throws naming the link.
void refuse_links_below(const std::filesystem::path& root, const std::filesystem::path& file);

// Where a case's image is accepted: folder mode's expected file, else its golden (variant).
std::filesystem::path bless_target(const Suite& suite, const Case& c, const std::string& image,
                                   const std::string& platform, const std::string& tag);

// The case's verdict into `r`, image by image; `prev`'s when neither its inputs nor its goldens
// changed (prev->judge_hash).
void judge_case(const Suite& suite, const Case& c, const std::string& platform, const RunOptions& o,
                const std::optional<CaseResult>& prev, CaseResult& r, CaseImages& images);

// Folder mode: an image only in the expected folder, a FAIL.
void judge_deleted(const Case& c, const RunOptions& o, CaseResult& r);

}  // namespace aosuite::harness

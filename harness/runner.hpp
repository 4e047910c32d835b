// Runs a suite's cases: render (or reuse an unchanged render), judge against the goldens, and
// record the result (check.cpp); and blesses goldens, only when asked (bless.cpp). The steps
// they share: selection.cpp, case_images.cpp, reuse_cache.cpp, case_verdict.cpp, run_cases.cpp.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "harness/results.hpp"
#include "harness/suite.hpp"

namespace aosuite::harness {

// Which cases a command acts on: a regular expression over case ids (searched, not anchored:
// "sao" keeps every SAO case; "^corner-front-sao-48x27$" exactly one) and a shard i of n
// (cases i, i+n, i+2n, ... of those the filter keeps).
struct Selection {
  std::string filter;  // empty: all
  int shard_index = 0, shard_count = 1;
};
// The shard from "i/n", else from GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS (as GoogleTest and
// Bazel set them), else 0/1. Throws std::invalid_argument on a malformed or impossible shard.
void set_shard(Selection& s, const std::string& text);
std::vector<const Case*> select(const Suite& suite, const Selection& s);
// select(), but an empty selection is an error (std::invalid_argument naming the suite and the
// command that lists its ids), found before anything is written: a run that judged nothing is
// never green and must not replace the last report.
std::vector<const Case*> select_some(const Suite& suite, const Selection& s);

struct RunOptions {
  Selection selection;
  int jobs = 1;
  std::filesystem::path report_dir;
  bool diff_all = false;  // diff images for passing cases too
  // --report-images: whether a passing case keeps its images (and its golden's copy) in the
  // report folder; false keeps only those of cases a reviewer must look at.
  bool passing_images = true;
  bool reuse = true;  // skip cases whose inputs and goldens are unchanged
  int retries = 0;    // run a failing case (FAIL or ERROR) up to this many times more
  // The platform key goldens are looked up under; empty: AOSUITE_PLATFORM, else the GL
  // renderer's when the selection renders a scene.
  std::string platform;
  std::function<void(const CaseResult&, int done, int total)> progress;
};

// Renders and judges the selected cases; writes images, per-case state and results.json into
// report_dir. Never touches goldens. Throws std::invalid_argument, before writing anything,
// when the selection is empty.
RunResults check(const Suite& suite, const RunOptions& options);

struct BlessOptions {
  RunOptions run;
  bool platform = false;  // write the platform's goldens instead of the generic ones
  std::string tag;        // write an extra accepted variant <image>~<tag>.png
  bool force = false;     // rewrite the goldens of cases that pass too
  // Accept the images of the last report in run.report_dir (what was reviewed) instead of
  // rendering; `failed`: every case that report says FAIL, NEW or WARN (and the selection keeps).
  bool from_report = false, failed = false;
};
// Writes goldens for the selected cases from fresh (or unchanged) renders, or from the last
// report's images (from_report, failed), each case's all or nothing (replace_goldens), after
// removing stale temporaries a killed bless left there. A case that passes is left alone
// (kPass, kept) unless `force`. A case that fails to render or to write is reported and its
// goldens are left alone. Returns one result per case: kPass when blessed or kept, kError (with
// the reason) when not. Throws std::invalid_argument for an empty selection (except `failed`
// with nothing failing: no cases), a tag that is not a valid_name(), or a report of another
// suite; std::runtime_error for a missing or malformed report.
RunResults bless(const Suite& suite, const BlessOptions& options);

// "aosuite bless SUITE [--goldens DIR]", shell-quoted.
std::string bless_prefix(const Suite& suite);
// The regular expression that matches exactly these case ids: ^id$ or ^(id|id...)$.
std::string exact_filter(const std::vector<std::string>& ids);
// `prefix` --filter '<exact_filter(ids)>': the command that blesses exactly these cases.
std::string bless_command(std::string_view prefix, const std::vector<std::string>& ids);
// `prefix` --failed --report 'DIR': the command that accepts what a report shows.
std::string accept_report_command(std::string_view prefix, const std::filesystem::path& report_dir);
// The report's page, as an absolute path.
std::string report_page(const std::filesystem::path& report_dir);
// Where a person reviews one case: the report page's panel for it, as an absolute path#case=ID.
std::string report_panel(const std::filesystem::path& report_dir, std::string_view case_id);

}  // namespace aosuite::harness

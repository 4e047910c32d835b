// check: each selected case's images made (or reused), judged, and recorded in the report folder.
#include <fmt/format.h>

#include "harness/case_images.hpp"
#include "harness/case_verdict.hpp"
#include "harness/reuse_cache.hpp"
#include "harness/run_cases.hpp"
#include "harness/runner.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

namespace {

// One attempt at a case: images, then the verdict.
void check_once(const Suite& suite, const std::string& environment, const std::string& platform,
                const RunOptions& o, const Cache& cache, Makers& makers, const Case& c,
                CaseResult& r) {
  if (c.source && c.source->deleted) {
    r.input_hash = r.judge_hash = "";
    judge_deleted(c, o, r);
    return;
  }
  CaseImages images;
  const auto prev = prepare_images(makers, environment, c, o, cache, r, images);
  judge_case(suite, c, platform, o, prev, r, images);
}

// --report-images failures: a passing case keeps its numbers and its goldens' paths, not its
// images, so a CI artifact carries what a reviewer looks at. Its next run makes them again
// (nothing to reuse). A folder that cannot be removed is only unreferenced bytes.
void leave_out_images(const fs::path& report_dir, CaseResult& r) {
  std::error_code ec;
  fs::remove_all(report_dir / "cases" / r.id, ec);
  r.files.clear(), r.failed_attempts.clear();
  r.images_left_out = true;
}

// Before a case runs again, its failing attempt's files are renamed attempt<k>_<file> in its
// report folder, so the report shows what failed beside what then passed.
Attempt keep_attempt(const fs::path& report_dir, const CaseResult& r, int k) {
  Attempt a{r.status, r.message, {}};
  const std::string prefix = fmt::format("attempt{}_", k);
  std::map<std::string, std::string> renamed;  // a golden identical to its image shares its file
  for (const auto& [role, rel] : r.files) {
    // An image's own role is set before it is made: a file there that this attempt did not
    // make (it failed first) is an earlier run's, not this attempt's.
    if (role.find(':') == std::string::npos && !r.image_hashes.contains(role)) continue;
    auto [it, fresh] = renamed.try_emplace(rel);
    if (fresh) {
      const fs::path from = report_dir / "cases" / rel;
      it->second = fs::path(rel).parent_path() / (prefix + from.filename().string());
      std::error_code ec;
      fs::rename(from, report_dir / "cases" / it->second, ec);
      if (ec) it->second.clear();  // not kept (never made): the page shows none
    }
    if (!it->second.empty()) a.files[role] = it->second;
  }
  return a;
}

}  // namespace

RunResults check(const Suite& suite, const RunOptions& o) {
  const std::vector<const Case*> cases = select_some(suite, o.selection);
  Makers first;
  RunResults run = start_run(suite, o, cases, true, first);
  const std::string environment = run.environment, platform = run.platform;
  const Cache cache = load_cache(o.report_dir);
  RunOptions again = o;
  again.reuse = false;
  run.cases =
      for_each_case(cases, o, std::move(first), [&](Makers& makers, const Case& c, CaseResult& r) {
        auto attempt = [&](const RunOptions& opts, CaseResult& into) {
          try {
            check_once(suite, environment, platform, opts, cache, makers, c, into);
          } catch (const std::exception& e) {
            into.status = Status::kError;
            into.message = e.what();
          }
        };
        attempt(o, r);
        std::vector<Attempt> failed;
        for (int k = 1; k <= o.retries && (r.status == Status::kFail || r.status == Status::kError);
             ++k) {
          failed.push_back(keep_attempt(o.report_dir, r, k));
          r = result_skeleton(c);
          attempt(again, r);
          r.attempts = k + 1;
          r.failed_attempts = failed;
          if (r.status == Status::kPass || r.status == Status::kWarn) {
            r.status = Status::kFlaky;
            r.message =
                fmt::format("failed, then passed on attempt {}: {}", k + 1, failed.front().message);
          }
        }
        if (awaits_approval(r.status)) {
          r.bless_command = bless_command(bless_prefix(suite), {c.id});
        }
        if (!o.passing_images && r.status == Status::kPass) leave_out_images(o.report_dir, r);
      });
  write_results(o.report_dir, run);
  save_cache(o.report_dir, cache, run.cases);
  return run;
}

}  // namespace aosuite::harness

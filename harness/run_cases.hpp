// What check and bless share around the cases: the run's header (paths, platform, the printed
// commands) and the cases run on -j threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "harness/case_images.hpp"
#include "harness/results.hpp"
#include "harness/runner.hpp"

namespace aosuite::harness {

// The run's header; makes the first scene case's maker into `first` when `may_render` (what it
// says of the machine names the platform), creates report_dir/cases and removes the last page.
// Throws std::invalid_argument for a platform that is not a valid_name().
RunResults start_run(const Suite& suite, const RunOptions& o, const std::vector<const Case*>& cases,
                     bool may_render, Makers& first);

// Runs `work(makers, case, result)` over the cases on `jobs` threads, each with its own makers
// (made when a case first needs one); `first` is the main thread's, reused by worker 0.
template <typename Work>
std::vector<CaseResult> for_each_case(const std::vector<const Case*>& cases, const RunOptions& o,
                                      Makers first, Work work) {
  std::vector<CaseResult> results(cases.size());
  std::atomic<std::size_t> next{0};
  std::atomic<int> done{0};
  std::mutex report;
  auto worker = [&](Makers makers) {
    for (std::size_t i; (i = next++) < cases.size();) {
      const auto t0 = std::chrono::steady_clock::now();
      CaseResult& r = results[i];
      r = result_skeleton(*cases[i]);
      try {
        work(makers, *cases[i], r);
      } catch (const std::exception& e) {
        r.status = Status::kError;
        r.message = e.what();
      }
      r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const std::lock_guard lock(report);
      if (o.progress) o.progress(r, ++done, static_cast<int>(cases.size()));
    }
  };
  const int jobs = std::max(1, std::min<int>(o.jobs, static_cast<int>(cases.size())));
  std::vector<std::thread> threads;
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker, Makers{});
  worker(std::move(first));
  for (std::thread& t : threads) t.join();
  return results;
}

}  // namespace aosuite::harness

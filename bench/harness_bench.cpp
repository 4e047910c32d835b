// The harness's saving on an unchanged re-run: every case of the default suite checked from
// scratch (render, compare, write) against the same run when inputs and goldens are unchanged
// and each case is taken from the previous run's report (content hash).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "ao/scene_cases.hpp"
#include "harness/runner.hpp"
#include "harness/suite_file.hpp"

namespace {

namespace fs = std::filesystem;
namespace hs = aosuite::harness;

const hs::Suite& default_suite() {
  static const hs::Suite s = [] {
    aosuite::ao::register_scene_cases();
    return hs::load_suite(fs::path(AOSUITE_SOURCE_DIR) / "suites/default.toml");
  }();
  return s;
}

void BM_CheckDefaultSuite(benchmark::State& state) {
  const bool reuse = state.range(0) != 0;
  hs::RunOptions o;
  o.report_dir = fs::temp_directory_path() / "aosuite-harness-bench";
  o.reuse = reuse;
  fs::remove_all(o.report_dir);
  hs::check(default_suite(), o);  // the run a re-run reuses; also warms llvmpipe's shaders
  for (auto _ : state) {
    if (hs::exit_code(hs::count(hs::check(default_suite(), o))) != 0) {
      state.SkipWithError("the default suite does not pass");
    }
  }
  fs::remove_all(o.report_dir);
}

BENCHMARK(BM_CheckDefaultSuite)->ArgName("reuse")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

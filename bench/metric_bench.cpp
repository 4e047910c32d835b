// The perceptual metric kernels at 1080p and 4K, in-process (images already in memory):
// FLIP LDR (8-bit sRGB), FLIP HDR (float RGB, ACES, automatic exposures), SSIM on 8-bit RGB;
// and every registered metric through the seam (compare/metric.hpp), BM_Metric/<name>.
// The pairs are tests/metric_pairs.hpp's bench_pair; `metric_oracle_inputs --bench DIR`
// writes the same pairs as files for timing the reference tools (bench/README.md).
#include <benchmark/benchmark.h>

#include <map>

#include "compare/metric.hpp"
#include "compare/metrics_cv.hpp"
#include "compare/opencv.hpp"
#include "tests/metric_pairs.hpp"

namespace {

const aosuite::test::MetricPair& pair_for(int height, bool hdr) {
  static std::map<std::pair<int, bool>, aosuite::test::MetricPair> cache;
  auto it = cache.find({height, hdr});
  if (it == cache.end())
    it = cache
             .emplace(std::pair{height, hdr},
                      aosuite::test::bench_pair(height * 16 / 9, height, hdr))
             .first;
  return it->second;
}

void set_pixels(benchmark::State& state, const cv::Mat& m) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * m.rows * m.cols);
}

void BM_FlipLdr(benchmark::State& state) {
  const auto& p = pair_for(static_cast<int>(state.range(0)), false);
  double mean = 0;
  for (auto _ : state) {
    const auto r = aosuite::flip::compare(p.a, p.b, false);
    benchmark::DoNotOptimize(r.error_map.data());
    mean = r.mean;
  }
  state.counters["mean"] = mean;
  set_pixels(state, p.a);
}

void BM_FlipHdr(benchmark::State& state) {
  const auto& p = pair_for(static_cast<int>(state.range(0)), true);
  int exposures = 0;
  double mean = 0;
  for (auto _ : state) {
    const auto r = aosuite::flip::compare(p.a, p.b, true);
    exposures = r.num_exposures;
    mean = r.mean;
  }
  state.counters["exposures"] = exposures;
  state.counters["mean"] = mean;
  set_pixels(state, p.a);
}

void BM_SsimRgb(benchmark::State& state) {
  const auto& p = pair_for(static_cast<int>(state.range(0)), false);
  double mean = 0;
  for (auto _ : state) {
    // (DoNotOptimize on a double lost the value with this GCC and benchmark 1.7.)
    const auto r = aosuite::ssim::compare(p.a, p.b);
    benchmark::ClobberMemory();
    mean = r.mean;
  }
  state.counters["ssim"] = mean;
  set_pixels(state, p.a);
}

// One registered metric on the 8-bit pair, as compare --metric and the harness call it.
void BM_Metric(benchmark::State& state, const aosuite::metric::Metric* m) {
  const auto& p = pair_for(static_cast<int>(state.range(0)), false);
  const aosuite::Picture a = aosuite::picture_of(p.a, "a"), b = aosuite::picture_of(p.b, "b");
  double value = 0;
  for (auto _ : state) {
    value = aosuite::metric::measure(*m, a, b).value(m->primary);
    benchmark::ClobberMemory();
  }
  state.counters[std::string(m->primary)] = value;
  set_pixels(state, p.a);
}

BENCHMARK(BM_FlipLdr)->Arg(1080)->Arg(2160)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FlipHdr)->Arg(1080)->Arg(2160)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_SsimRgb)->Arg(1080)->Arg(2160)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  for (const aosuite::metric::Metric* m : aosuite::metric::all()) {
    benchmark::RegisterBenchmark(("BM_Metric/" + std::string(m->name)).c_str(), BM_Metric, m)
        ->Arg(1080)
        ->Arg(2160)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

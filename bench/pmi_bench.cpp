// Viewpoint-based AO (PMI) on the Stanford dragon: the item buffer (ID draw + GPU histogram +
// counter read-back) per viewpoint at the paper's three resolutions, the per-polygon
// accumulation per viewpoint, and the whole channel for the smaller viewpoint spheres. The
// paper's Table 1 (all 12 x 3 cases, with errors) is `aosuite pmi-study` (docs/results.md).
// llvmpipe on the CPU: read the figures as relative costs.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "bench/bench_main.hpp"
#include "renderer/pmi/pmi_item_buffer.hpp"
#include "renderer/pmi/viewpoint_sphere.hpp"
#include "renderer/renderer.hpp"

namespace {

namespace rd = aosuite::renderer;

using aosuite::bench::bench_renderer;

// The dragon when scripts/fetch_assets.sh has run, else the built-in spheres.
const rd::PmiObject& object() {
  static const rd::PmiObject o = rd::pmi_object(rd::builtin_scene(
      std::filesystem::exists(rd::downloadable_scene_file("dragon")) ? "dragon" : "spheres"));
  return o;
}

void BM_ItemBufferCount(benchmark::State& state) {
  bench_renderer();
  const int w = static_cast<int>(state.range(0));
  rd::ItemBuffer items(object(), w, w * 3 / 4);
  const std::vector<glm::vec3> dirs = rd::make_icosphere(42).vertices;
  std::size_t v = 0;
  items.count(object().centre + dirs[0]);  // warm-up: llvmpipe compiles the shaders
  for (auto _ : state) {
    const glm::vec3 eye = object().centre + dirs[v++ % dirs.size()] * (3 * object().radius);
    benchmark::DoNotOptimize(items.count(eye).data());
  }
  state.counters["polygons"] = static_cast<double>(object().triangles.size());
}

void BM_Accumulate(benchmark::State& state) {
  bench_renderer();
  const int w = static_cast<int>(state.range(0));
  rd::ItemBuffer items(object(), w, w * 3 / 4);
  const std::vector<std::uint32_t> counts =
      items.count(object().centre + glm::vec3(0, 0, 3 * object().radius));
  rd::PmiAccumulator acc(counts.size());
  for (auto _ : state) acc.add_view(counts);
  benchmark::DoNotOptimize(acc.pmi().data());
}

void BM_Channel(benchmark::State& state) {
  bench_renderer();
  rd::PmiSettings s;
  s.width = static_cast<int>(state.range(0)), s.height = s.width * 3 / 4;
  s.viewpoints = static_cast<int>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(rd::compute_pmi_channel(object(), s).pmi.data());
}

BENCHMARK(BM_ItemBufferCount)->Arg(640)->Arg(1280)->Arg(2560)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Accumulate)->Arg(640)->Arg(1280)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Channel)
    ->Args({640, 12})
    ->Args({640, 42})
    ->Args({1280, 12})
    ->Args({1280, 42})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

}  // namespace

AOSUITE_RENDERING_BENCHMARK_MAIN()

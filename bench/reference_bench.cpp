// Ray-traced reference throughput (rays per second) on the village street view: the G-buffer
// is rendered once, then the reference is traced with 256 cosine-weighted rays per pixel at
// Alchemy's default radius (ao), and unbounded.
#include <benchmark/benchmark.h>

#include "bench/bench_main.hpp"
#include "reference/reference_ao.hpp"
#include "renderer/renderer.hpp"

namespace {

namespace rd = aosuite::renderer;
using aosuite::bench::bench_renderer;
namespace ref = aosuite::reference;

const rd::Scene& village() {
  static const rd::Scene s = rd::builtin_scene("village");
  return s;
}

void BM_Reference(benchmark::State& state, ref::Variant variant) {
  const auto w = static_cast<int>(state.range(0)), h = w * 9 / 16;
  rd::RenderSettings s;
  s.width = w, s.height = h;
  s.outputs = rd::parse_outputs("ao_float");
  s.outputs.normal = true;
  const rd::View& view = village().views[0];
  const rd::Images img = bench_renderer().render(village(), view, s);
  const ref::EmbreeScene scene(village());
  const ref::ReferenceSettings settings{256, 1, variant};
  const double rays = settings.rays * cv::countNonZero(img.depth > 0);
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        ref::reference_ao(scene, rd::make_camera(view, w, h), img.depth, img.normal, settings));
  }
  state.counters["rays_per_s"] = benchmark::Counter(rays * static_cast<double>(state.iterations()),
                                                    benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_Reference, ao_r1, ref::Variant::kAo)
    ->Arg(320)
    ->Arg(1920)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_Reference, unbounded, ref::Variant::kUnbounded)
    ->Arg(320)
    ->Arg(1920)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

AOSUITE_RENDERING_BENCHMARK_MAIN()

// Each renderer pass per technique, and the savings of skipping work: only the no-AO image
// asked for, MSSAO with zero-weight coarse levels, and a frame that is mostly sky.
// llvmpipe on the CPU: read the figures as relative costs, not GPU milliseconds.
#include <benchmark/benchmark.h>

#include <map>

#include "bench/bench_main.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene.hpp"

namespace {

namespace rd = aosuite::renderer;

rd::Renderer& renderer() {
  static rd::Renderer r;
  return r;
}

const rd::Scene& village() {
  static const rd::Scene s = rd::builtin_scene("village");
  return s;
}

// Reports each pass's GL time as a counter (mean over iterations) beside the frame time.
void run(benchmark::State& state, const rd::Scene& scene, const rd::View& view,
         const rd::RenderSettings& s) {
  renderer().render(scene, view, s);  // warm-up: llvmpipe compiles shader variants
  std::map<std::string, double> pass_ms;
  for (auto _ : state) {
    for (const rd::PassTime& t : renderer().render(scene, view, s).times)
      pass_ms[t.pass] += t.gpu_ms;
  }
  for (const auto& [pass, ms] : pass_ms) {
    state.counters[pass + "_ms"] = ms / static_cast<double>(state.iterations());
  }
}

rd::RenderSettings settings(rd::Technique t, int width, int height) {
  rd::RenderSettings s;
  s.width = width, s.height = height, s.technique = t, s.params = rd::default_params(t);
  return s;
}

void BM_Frame(benchmark::State& state, rd::Technique t) {
  const auto w = static_cast<int>(state.range(0)), h = w * 9 / 16;
  run(state, village(), village().views[0], settings(t, w, h));
}

void BM_OnlyNoAoImage(benchmark::State& state) {  // saving: AO and blur not run
  rd::RenderSettings s = settings(rd::Technique::kAlchemy, 640, 360);
  s.outputs = rd::parse_outputs("no_ao");
  run(state, village(), village().views[0], s);
}

void BM_MssaoTwoLevels(benchmark::State& state) {  // saving: levels 2..4 weigh 0
  rd::RenderSettings s = settings(rd::Technique::kMssao, 640, 360);
  s.params.level_weights = {1.0f, 0.5f, 0, 0, 0};
  run(state, village(), village().views[0], s);
}

void BM_MostlySky(benchmark::State& state) {  // saving: background pixels skip AO and blur
  rd::View up = village().views[0];
  up.target = up.eye + glm::vec3(0.2f, 1, 0);  // looking up past the roofs
  run(state, village(), up, settings(rd::Technique::kAlchemy, 640, 360));
}

BENCHMARK_CAPTURE(BM_Frame, alchemy, rd::Technique::kAlchemy)
    ->Arg(640)
    ->Arg(1920)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame, sao, rd::Technique::kSao)
    ->Arg(640)
    ->Arg(1920)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame, mssao, rd::Technique::kMssao)
    ->Arg(640)
    ->Arg(1920)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame, ue4, rd::Technique::kUe4)
    ->Arg(640)
    ->Arg(1920)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OnlyNoAoImage)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MssaoTwoLevels)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MostlySky)->Unit(benchmark::kMillisecond);

}  // namespace

AOSUITE_RENDERING_BENCHMARK_MAIN()

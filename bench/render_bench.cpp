// Each renderer pass per technique and pipeline (fragment draws or compute dispatches, the same
// images), GTAO's exact_plane path, and the savings of skipping work:
// only the no-AO image asked for, MSSAO with zero-weight coarse levels, and a frame that is
// mostly sky.
// The "gl" line of the context names the device: on llvmpipe read the figures as relative
// costs, on a GPU as its milliseconds.
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include "bench/bench_main.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene.hpp"

namespace {

namespace rd = aosuite::renderer;

using aosuite::bench::bench_renderer;

const rd::Scene& village() {
  static const rd::Scene s = rd::builtin_scene("village");
  return s;
}

// Reports each pass's GPU time and the frame's wall time before read-back as counters (means
// over iterations) beside the whole frame's time.
void run(benchmark::State& state, const rd::Scene& scene, const rd::View& view,
         const rd::RenderSettings& s) {
  bench_renderer().render(scene, view, s);  // warm-up: llvmpipe compiles shader variants
  std::map<std::string, double> pass_ms;
  for (auto _ : state) {
    const rd::Images img = bench_renderer().render(scene, view, s);
    for (const rd::PassTime& t : img.times) pass_ms[t.pass] += t.gpu_ms;
    pass_ms["frame_wall"] += img.frame_ms;
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

void BM_Frame(benchmark::State& state, rd::Technique t, rd::Pipeline pipeline) {
  const auto w = static_cast<int>(state.range(0)), h = w * 9 / 16;
  rd::RenderSettings s = settings(t, w, h);
  s.pipeline = pipeline;
  run(state, village(), village().views[0], s);
}

void BM_OnlyNoAoImage(benchmark::State& state) {  // saving: AO and blur not run
  rd::RenderSettings s = settings(rd::Technique::kAlchemy, 640, 360);
  s.outputs = rd::parse_outputs("no_ao");
  run(state, village(), village().views[0], s);
}

void BM_MssaoTwoLevels(benchmark::State& state) {  // saving: levels 2..4 weigh 0
  rd::RenderSettings s = settings(rd::Technique::kMssao, 640, 360);
  s.params.mssao.level_weights = {1.0f, 0.5f, 0, 0, 0};
  run(state, village(), village().views[0], s);
}

// GTAO's exact_plane path: one gather of four depths per horizon sample instead of one fetch,
// and a division per pixel; beside BM_Frame/gtao at the same size, its cost.
void BM_GtaoExactPlane(benchmark::State& state) {
  const auto w = static_cast<int>(state.range(0)), h = w * 9 / 16;
  rd::RenderSettings s = settings(rd::Technique::kGtao, w, h);
  s.params.gtao.exact_plane = 1;
  run(state, village(), village().views[0], s);
}

void BM_MostlySky(benchmark::State& state) {  // saving: background pixels skip AO and blur
  rd::View up = village().views[0];
  up.target = up.eye + glm::vec3(0.2f, 1, 0);  // looking up past the roofs
  run(state, village(), up, settings(rd::Technique::kAlchemy, 640, 360));
}

// One frame benchmark per registered technique (renderer/technique.hpp) and pipeline,
// BM_Frame/TECHNIQUE/PIPELINE/WIDTH, so a new technique is measured without an edit here. PMI's
// first frame (the warm-up) builds its cached maps; its own pass is rasterised in both.
const bool kFramesRegistered = [] {
  for (const rd::TechniqueInfo& t : rd::techniques()) {
    for (rd::Pipeline p : {rd::Pipeline::kFragment, rd::Pipeline::kCompute}) {
      const std::string name =
          "BM_Frame/" + std::string(t.name) + "/" + std::string(rd::pipeline_name(p));
      benchmark::RegisterBenchmark(name.c_str(), BM_Frame, t.id, p)
          ->Arg(640)
          ->Arg(1920)
          ->Arg(3840)
          ->Unit(benchmark::kMillisecond);
    }
  }
  return true;
}();
BENCHMARK(BM_OnlyNoAoImage)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MssaoTwoLevels)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MostlySky)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GtaoExactPlane)->Arg(640)->Arg(1920)->Unit(benchmark::kMillisecond);

}  // namespace

AOSUITE_RENDERING_BENCHMARK_MAIN()

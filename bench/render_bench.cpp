// Each renderer pass per technique and pipeline (fragment draws or compute dispatches, the same
// images), GTAO's exact_plane path, and the savings of skipping work:
// only the no-AO image asked for, MSSAO with zero-weight coarse levels, and a frame that is
// mostly sky.
// The "gl" line of the context names the device: on llvmpipe read the figures as relative
// costs, on a GPU as its milliseconds.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "bench/bench_main.hpp"
#include "renderer/passes/gbuffer_pass.hpp"
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

// The AO pass at half the width and height (half_res=1, the `half` preset), downsample and
// upsample included: beside BM_Frame/TECHNIQUE/PIPELINE at the same size, what it saves.
void BM_FrameHalf(benchmark::State& state, rd::Technique t, rd::Pipeline pipeline) {
  const auto w = static_cast<int>(state.range(0)), h = w * 9 / 16;
  rd::RenderSettings s = settings(t, w, h);
  s.pipeline = pipeline;
  s.params.half_res = 1;
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

// The G-buffer two ways (issue 44): the full pass (linear depth, normals and albedo drawn by a
// fragment shader) against XeGTAO's depth-only rasterisation plus a compute pass that
// reconstructs depth and normals. Counters: each part's GPU time, and for depth_only how far
// its normals turn from the rasterised ones (mean and 95th percentile, degrees, geometry
// pixels), the accuracy half of the question.
std::vector<glm::vec4> normals(const rd::GBuffer& g) {
  std::vector<glm::vec4> n(static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height));
  rd::glGetTextureImage(g.normal.get(), 0, GL_RGBA, GL_FLOAT,
                        static_cast<GLsizei>(n.size() * sizeof(glm::vec4)), n.data());
  return n;
}

void normal_error_counters(benchmark::State& state, const std::vector<glm::vec4>& raster,
                           const std::vector<glm::vec4>& rebuilt) {
  std::vector<double> degrees;
  for (std::size_t i = 0; i < raster.size(); ++i) {
    if (glm::dot(glm::vec3(raster[i]), glm::vec3(raster[i])) < 0.5f) continue;  // sky
    // atan2, not acos of the dot product: RGBA16F normals are unit only to about 1e-3, which
    // acos reads as 2 degrees.
    const glm::vec3 a(raster[i]), b(rebuilt[i]);
    degrees.push_back(glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b))));
  }
  if (degrees.empty()) return;
  double sum = 0;
  for (double d : degrees) sum += d;
  const auto p95 = degrees.begin() + static_cast<std::ptrdiff_t>(degrees.size() * 95 / 100);
  std::nth_element(degrees.begin(), p95, degrees.end());
  state.counters["normal_mean_deg"] = sum / static_cast<double>(degrees.size());
  state.counters["normal_p95_deg"] = *p95;
}

void BM_GBuffer(benchmark::State& state, bool depth_only) {
  const auto w = static_cast<int>(state.range(0)), h = w * 9 / 16;
  bench_renderer();  // the GL context
  const rd::GpuScene scene(village());
  const rd::Camera camera = rd::make_camera(village().views[0], w, h);
  const rd::GBuffer g = rd::make_gbuffer(w, h);
  rd::GBufferPass full;
  rd::DepthGBufferPass depth;
  std::map<std::string, double> pass_ms;
  for (int warm_up = 0; warm_up < 2; ++warm_up) {
    full.run(scene, camera, g);
    if (depth_only) depth.run(scene, camera, g);
  }
  rd::glFinish();
  for (auto _ : state) {
    std::vector<rd::PassTimer> timers;
    if (depth_only) {
      timers = depth.run(scene, camera, g);
    } else {
      timers.emplace_back("gbuffer");
      full.run(scene, camera, g);
      timers.back().stop();
    }
    for (const rd::PassTimer& t : timers) pass_ms[t.read().pass] += t.read().gpu_ms;
  }
  for (const auto& [pass, ms] : pass_ms) {
    state.counters[pass + "_ms"] = ms / static_cast<double>(state.iterations());
  }
  if (depth_only) {
    full.run(scene, camera, g);
    const std::vector<glm::vec4> raster = normals(g);
    depth.run(scene, camera, g);
    normal_error_counters(state, raster, normals(g));
  }
}
BENCHMARK_CAPTURE(BM_GBuffer, full, false)->Arg(1920)->Arg(3840)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_GBuffer, depth_only, true)
    ->Arg(1920)
    ->Arg(3840)
    ->Unit(benchmark::kMillisecond);

// One frame benchmark per registered technique (renderer/technique.hpp) and pipeline,
// BM_Frame/TECHNIQUE/PIPELINE/WIDTH (and BM_FrameHalf/... for the screen-space ones), so a new
// technique is measured without an edit here. PMI's
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
      if (t.space != rd::Space::kScreen) continue;
      const std::string half =
          "BM_FrameHalf/" + std::string(t.name) + "/" + std::string(rd::pipeline_name(p));
      benchmark::RegisterBenchmark(half.c_str(), BM_FrameHalf, t.id, p)
          ->Arg(640)
          ->Arg(1920)
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

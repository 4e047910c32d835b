#include "ao/sweep_run.hpp"

#include <optional>

#include "ao/timed_render.hpp"
#include "reference/frame_error.hpp"
#include "reference/reference_cache.hpp"
#include "renderer/params.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::ao {
namespace {

namespace rd = aosuite::renderer;
namespace ref = aosuite::reference;

std::vector<const rd::View*> pick_views(const rd::Scene& scene,
                                        const std::vector<std::string>& names) {
  std::vector<const rd::View*> views;
  if (names.empty()) {
    for (const rd::View& v : scene.views) views.push_back(&v);
  } else {
    for (const std::string& n : names) views.push_back(&rd::find_view(scene, n));
  }
  return views;
}

// Renders and measures the configurations of one view that `shard` takes; `index` counts
// every configuration of the grid, taken or not, so each has the same number in every shard.
// References are traced (or read from the cache) only for what the shard runs.
void sweep_view(rd::Renderer& renderer, const SweepGrid& g, const harness::Selection& shard,
                const rd::Scene& scene, ref::ReferenceCache& cache, const rd::View& view,
                std::size_t view_index, int w, int h, std::size_t& index, std::vector<Row>& rows,
                const std::function<void(const Row&)>& on_row) {
  const rd::Camera camera = rd::make_camera(view, w, h);
  std::optional<rd::Images> gbuffer;
  auto reference = [&](const ref::ReferenceSettings& rs) {
    if (!gbuffer) gbuffer = renderer.render(scene, view, rd::gbuffer_settings(w, h));
    return cache.get(camera, gbuffer->depth, gbuffer->normal, rs);
  };
  const ref::MetricOptions metric{8, 0.05f, g.rays};
  cv::Mat unbounded;
  for (const TechniqueGrid& tg : g.techniques) {
    const std::vector<float> intensities =
        tg.intensities.empty() ? std::vector<float>{rd::default_params(tg.technique).intensity}
                               : tg.intensities;
    for (int samples : tg.samples) {
      for (float radius : tg.radii) {
        cv::Mat at_radius;
        for (float intensity : intensities) {
          const std::size_t i = index++;
          if (static_cast<int>(i % static_cast<std::size_t>(shard.shard_count)) !=
              shard.shard_index)
            continue;
          if (at_radius.empty()) at_radius = reference({g.rays, radius, ref::Variant::kAo});
          if (g.unbounded && unbounded.empty())
            unbounded = reference({g.rays, 1, ref::Variant::kUnbounded});
          rd::RenderSettings s;
          s.width = w, s.height = h, s.technique = tg.technique;
          s.params = rd::default_params(tg.technique);
          for (const auto& [k, v] : tg.params) rd::set_param(s.params, k, v);
          if (samples > 0) s.params.samples = samples;
          s.params.radius = radius, s.params.intensity = intensity;
          s.outputs = rd::parse_outputs("no_ao,ao_float");  // no_ao: the frame error's lighting
          s.pipeline = g.pipeline;
          const Timed t = render_timed(renderer, scene, view, s, g.runs);
          Row row{i,
                  scene.name,
                  view.name,
                  view_index,
                  tg.technique,
                  w,
                  h,
                  samples,
                  radius,
                  intensity,
                  t.gl_ms,
                  t.images.geometry_pixels,
                  ref::measure_error(t.images.ao, at_radius, t.images.depth, metric),
                  {},
                  {},
                  tg.params};
          if (g.unbounded)
            row.unbounded = ref::measure_error(t.images.ao, unbounded, t.images.depth, metric).all;
          row.frame = ref::frame_error(t.images.no_ao, t.images.ao, at_radius, t.images.depth);
          on_row(row);
          rows.push_back(std::move(row));
        }
      }
    }
  }
}

}  // namespace

SweepResult run_sweep(const SweepGrid& g, const harness::Selection& shard,
                      const std::function<void(const Row&)>& on_row) {
  rd::Renderer renderer;
  std::vector<Row> rows;
  std::size_t index = 0;
  for (const std::string& name : g.scenes) {
    const rd::Scene scene = rd::load_scene(name);
    const std::vector<const rd::View*> views = pick_views(scene, g.views);
    ref::ReferenceCache cache(scene, ref::default_cache_dir());
    for (const auto& [w, h] : g.resolutions) {
      for (std::size_t v = 0; v < views.size(); ++v)
        sweep_view(renderer, g, shard, scene, cache, *views[v], v, w, h, index, rows, on_row);
    }
  }
  return {{g.name, renderer.gl_description(), renderer.gl_source(),
           std::string(rd::pipeline_name(g.pipeline.value_or(renderer.default_pipeline()))), g.rays,
           g.runs, g.unbounded, index},
          std::move(rows)};
}

}  // namespace aosuite::ao

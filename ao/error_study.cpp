#include "ao/error_study.hpp"

#include "ao/error_json.hpp"
#include "reference/reference_cache.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::ao {

namespace rd = aosuite::renderer;
namespace ref = aosuite::reference;

ErrorStudy measure_error_study(const CaseOptions& c, const std::string& variant, int rays) {
  const rd::Scene scene = rd::load_scene(c.scene);
  const rd::View& view = rd::find_view(scene, c.view);
  ErrorStudy e;
  e.scene = scene.name, e.view = view.name;
  e.settings = case_settings(c);
  rd::RenderSettings& s = e.settings;
  s.outputs = rd::parse_outputs("no_ao,ao_float");  // no_ao: the frame error's lighting
  s.outputs.normal = true;
  e.reference_settings = {rays, s.params.radius, ref::parse_variant(variant)};
  const ref::ReferenceSettings& rs = e.reference_settings;
  ref::validate(rs);

  rd::Renderer renderer;
  const rd::Images img = renderer.render(scene, view, s);
  s.pipeline = img.pipeline;  // the one that ran, for the JSON
  ref::ReferenceCache cache(scene, ref::default_cache_dir());
  const rd::Camera camera = rd::make_camera(view, s.width, s.height);
  // The reference is traced over the full G-buffer, the true surfaces, whichever G-buffer the
  // technique read: a depth-only one's reconstructed normals would move the yardstick too.
  const rd::Images surfaces =
      s.gbuffer == rd::GBufferKind::kFull
          ? img
          : renderer.render(scene, view, rd::gbuffer_settings(s.width, s.height));
  e.reference = cache.get(camera, surfaces.depth, surfaces.normal, rs);
  e.reference_cached = cache.last_was_cached(), e.reference_seconds = cache.last_seconds();
  e.ao = img.ao, e.depth = img.depth;
  e.error = ref::measure_error(img.ao, e.reference, img.depth, {8, 0.05f, rs.rays});
  e.frame = ref::frame_error(img.no_ao, img.ao, e.reference, img.depth);
  return e;
}

nlohmann::ordered_json error_study_json(const ErrorStudy& e, const CaseOptions& c,
                                        const std::string& variant) {
  const rd::RenderSettings& s = e.settings;
  const ref::ReferenceSettings& rs = e.reference_settings;
  nlohmann::ordered_json j;
  j["scene"] = e.scene, j["view"] = e.view, j["technique"] = c.technique;
  j["width"] = s.width, j["height"] = s.height;
  j["samples"] = s.params.samples, j["radius"] = s.params.radius;
  j["intensity"] = s.params.intensity;
  j["params"] = params_json(s.technique, s.params);
  if (s.pipeline) j["pipeline"] = rd::pipeline_name(*s.pipeline);
  j["gbuffer"] = rd::gbuffer_name(s.gbuffer);
  j["reference"] = {{"variant", variant},
                    {"rays", rs.rays},
                    {"radius", rs.radius},
                    {"cached", e.reference_cached},
                    {"seconds", e.reference_seconds}};
  j["error"] = to_json(e.error);
  j["frame"] = to_json(e.frame);
  return j;
}

}  // namespace aosuite::ao

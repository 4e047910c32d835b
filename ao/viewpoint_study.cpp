#include "ao/viewpoint_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "ao/colour_ao_ply.hpp"
#include "ao/viewpoint_sphere_scene.hpp"
#include "compare/opencv.hpp"
#include "renderer/pmi/pmi_object.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::ao {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;

nlohmann::ordered_json run_viewpoint_study(const ViewpointStudySettings& a) {
  const rd::Scene scene = rd::load_scene(a.scene);
  rd::PmiSettings ps;
  ps.viewpoints = a.viewpoints, ps.width = a.resolution,
  ps.height = std::max(1, a.resolution * 3 / 4);
  ps.importance_best = a.importance_best, ps.per_view = true, ps.colour = a.colour_ao;
  rd::Renderer renderer;
  const auto maps = renderer.pmi_maps(scene, ps);
  const rd::PmiChannel& c = maps->channel;
  const fs::path dir(a.out);
  fs::create_directories(dir);

  std::string csv = "viewpoint,x,y,z,p_v,vmi,pmi_v\n";
  for (std::size_t v = 0; v < c.viewpoints.size(); ++v) {
    const glm::vec3 p = c.viewpoints[v];
    csv += fmt::format("{},{},{},{},{},{},{}\n", v, p.x, p.y, p.z, c.view_probability[v], c.vmi[v],
                       c.view_pmi[v]);
  }
  write_text(dir / (scene.name + "_viewpoints.csv"), csv);
  if (a.colour_ao) write_colour_ao(dir / (scene.name + "_colour_ao.ply"), maps->object, c);

  // The views: the object alone (a ground plane would hide it from the lower half).
  rd::Scene object = scene;
  std::erase_if(object.meshes, [](const rd::Mesh& m) { return m.ground; });
  rd::RenderSettings rs;
  rs.width = a.width, rs.height = a.height, rs.technique = rd::Technique::kPmi;
  rs.params = rd::default_params(rs.technique);
  rs.params.pmi = {a.viewpoints, a.resolution, a.importance_best};
  rs.outputs = rd::parse_outputs("with_ao");
  const auto by_pmi = std::minmax_element(c.view_pmi.begin(), c.view_pmi.end());
  const auto by_vmi = std::minmax_element(c.vmi.begin(), c.vmi.end());
  auto index = [&](auto it, const std::vector<double>& of) {
    return static_cast<std::size_t>(it - of.begin());
  };
  nlohmann::ordered_json j;
  j["scene"] = scene.name, j["viewpoints"] = a.viewpoints;
  j["item_buffer"] = fmt::format("{}x{}", ps.width, ps.height);
  j["importance_best"] = a.importance_best;
  j["best_pmi_v"] = index(by_pmi.second, c.view_pmi),
  j["worst_pmi_v"] = index(by_pmi.first, c.view_pmi);
  // VMI's best view is its minimum (Feixas et al. 2009: the most balanced projection).
  j["best_vmi"] = index(by_vmi.first, c.vmi), j["worst_vmi"] = index(by_vmi.second, c.vmi);
  for (const auto& [name, v] : {std::pair{"best", index(by_pmi.second, c.view_pmi)},
                                std::pair{"worst", index(by_pmi.first, c.view_pmi)}}) {
    // The object's own bounding sphere: the scene's, less the ground, equals the PMI object's.
    rd::View view = rd::viewpoint_view(maps->object, c.viewpoints[v]);
    view.name = name;
    const rd::Images img = renderer.render(object, view, rs);
    write_png_rgba8(dir / fmt::format("{}_{}_view.png", scene.name, name), img.with_ao);
  }
  std::vector<glm::vec3> directions;
  for (const glm::vec3& p : c.viewpoints)
    directions.push_back(glm::normalize(p - maps->object.centre));
  rd::Scene sphere = coloured_sphere(directions, c.view_pmi);
  rs.technique = rd::Technique::kAlchemy, rs.outputs = rd::parse_outputs("no_ao");
  for (const auto& [name, eye] :
       {std::pair{"front", glm::vec3(0, 1, 3.2f)}, std::pair{"back", glm::vec3(0, 1, -3.2f)}}) {
    const rd::View view{name, eye, glm::vec3(0), glm::vec3(0, 1, 0), 45, 0.1f};
    write_png_rgba8(dir / fmt::format("{}_sphere_{}.png", scene.name, name),
                    renderer.render(sphere, view, rs).no_ao);
  }
  write_text(dir / (scene.name + "_viewpoints.json"), j.dump(2) + "\n");
  return j;
}

}  // namespace aosuite::ao

// `aosuite viewpoints`: viewpoint selection with PMI's channel (González et al. 2008): VMI
// I(v;O) and PMI(v) = sum_o p(v|o) PMI(o) per viewpoint, the most and least informative views
// (by PMI(v), as the paper's Figure 6: the best sees the most PMI) and the viewpoint sphere
// coloured by PMI(v), cold to warm, from the front (+z) and the back.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "compare/opencv.hpp"
#include "renderer/pmi/viewpoint_sphere.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::cli {
namespace {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;

struct ViewpointsArgs {
  std::string scene = "dragon", out = "reports/viewpoints";
  int viewpoints = 162, resolution = 1280, importance_best = 0, width = 640, height = 480;
  bool colour_ao = false;
};

// Cold (low) to warm (high), as the paper's spheres.
glm::vec3 heat(float t) {
  const glm::vec3 stops[] = {
      {0.1f, 0.2f, 0.9f}, {0.1f, 0.8f, 0.9f}, {0.95f, 0.9f, 0.2f}, {0.9f, 0.15f, 0.1f}};
  const float x = std::clamp(t, 0.0f, 1.0f) * 3;
  const int i = std::min(2, static_cast<int>(x));
  return glm::mix(stops[i], stops[i + 1], x - static_cast<float>(i));
}

// The viewpoint sphere as cells, one per viewpoint (faces of a finer sphere coloured by their
// nearest viewpoint), in 64 colour bands of `value` (one mesh per band).
rd::Scene coloured_sphere(const std::vector<glm::vec3>& directions,
                          const std::vector<double>& value) {
  const auto [lo, hi] = std::minmax_element(value.begin(), value.end());
  const rd::Icosphere fine = rd::make_icosphere(
      std::min<int>(2562, static_cast<int>(directions.size()) * 16 - 30));  // two more subdivisions
  constexpr int kBands = 64;
  rd::Scene s{"viewpoint_sphere", std::vector<rd::Mesh>(kBands), {}};
  for (const glm::uvec3& f : fine.faces) {
    const glm::vec3 c =
        glm::normalize(fine.vertices[f.x] + fine.vertices[f.y] + fine.vertices[f.z]);
    std::size_t nearest = 0;
    for (std::size_t v = 1; v < directions.size(); ++v)
      if (glm::dot(c, directions[v]) > glm::dot(c, directions[nearest])) nearest = v;
    const double t = *hi > *lo ? (value[nearest] - *lo) / (*hi - *lo) : 0.5;
    rd::Mesh& band = s.meshes[std::min(kBands - 1, static_cast<int>(t * kBands))];
    const auto base = static_cast<unsigned>(band.positions.size());
    for (unsigned i : {f.x, f.y, f.z}) band.positions.push_back(fine.vertices[i]);
    band.triangles.emplace_back(base, base + 1, base + 2);
  }
  for (int b = 0; b < kBands; ++b) {
    s.meshes[b].colour = heat((static_cast<float>(b) + 0.5f) / kBands);
    rd::compute_normals(s.meshes[b]);
  }
  return s;
}

// Colour AO (the paper's eq. 12) per vertex as an ASCII PLY with vertex colours.
void write_colour_ao(const fs::path& path, const rd::PmiObject& object,
                     const rd::PmiChannel& channel) {
  const std::vector<glm::vec3> polygon = rd::polygon_colour_visibility(channel);
  std::vector<float> per_vertex[3];
  for (int a = 0; a < 3; ++a) {
    std::vector<float> one(polygon.size());
    for (std::size_t o = 0; o < one.size(); ++o) one[o] = polygon[o][a];
    per_vertex[a] = rd::vertex_visibility(object, one);
  }
  std::string ply = fmt::format(
      "ply\nformat ascii 1.0\ncomment colour ambient occlusion (PMI, eq. 12)\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
      object.positions.size(), object.triangles.size());
  auto byte = [](float x) {
    return static_cast<int>(std::lround(std::clamp(x, 0.0f, 1.0f) * 255));
  };
  for (std::size_t i = 0; i < object.positions.size(); ++i) {
    const glm::vec3 p = object.positions[i];
    ply += fmt::format("{} {} {} {} {} {}\n", p.x, p.y, p.z, byte(per_vertex[0][i]),
                       byte(per_vertex[1][i]), byte(per_vertex[2][i]));
  }
  for (const glm::uvec3& t : object.triangles) ply += fmt::format("3 {} {} {}\n", t.x, t.y, t.z);
  write_text(path, ply);
}

int run_viewpoints(const ViewpointsArgs& a) {
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
  fmt::print("{}\n", j.dump());
  return kExitSame;
}

}  // namespace

void add_viewpoints_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<ViewpointsArgs>();
  CLI::App* cmd = app.add_subcommand(
      "viewpoints", "PMI viewpoint selection: VMI and PMI(v) per viewpoint, best/worst views");
  cmd->add_option("--scene", a->scene, "built-in scene or scene file")->capture_default_str();
  cmd->add_option("--viewpoints", a->viewpoints, "12, 42, 162, 642 or 2562")->capture_default_str();
  cmd->add_option("--resolution", a->resolution, "item-buffer width (height 3/4 of it)")
      ->capture_default_str();
  cmd->add_option("--importance-best", a->importance_best,
                  "0: p(v) by projected area; k: the k best views share 99 %")
      ->capture_default_str();
  cmd->add_flag("--colour-ao", a->colour_ao,
                "also write colour AO (eq. 12; viewpoint colours (1 + direction) / 2) as a PLY");
  cmd->add_option("--width", a->width, "view image width")->capture_default_str();
  cmd->add_option("--height", a->height, "view image height")->capture_default_str();
  cmd->add_option("--out", a->out)->capture_default_str();
  guarded(cmd, rc, "viewpoints", [a] { return run_viewpoints(*a); });
}

}  // namespace aosuite::cli

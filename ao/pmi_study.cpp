#include "ao/pmi_study.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include "ao/pmi_smoothness.hpp"
#include "ao/pmi_vertex_ao.hpp"
#include "ao/statistics.hpp"
#include "compare/opencv.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::ao {
namespace {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

std::string run_pmi_study(const PmiStudySettings& a, const PmiStudyProgress& progress) {
  const rd::Scene scene = rd::load_scene(a.scene);
  rd::Renderer renderer;  // the GL context
  const rd::PmiObject object = rd::pmi_object(scene);
  std::vector<glm::vec3> normals;
  for (const rd::Mesh& m : scene.meshes) {
    if (m.ground) continue;
    for (std::size_t i = 0; i < m.positions.size(); ++i)
      normals.push_back(i < m.normals.size() ? m.normals[i] : glm::vec3(0));
  }
  auto start = std::chrono::steady_clock::now();
  const std::vector<float> traced = ray_traced_vertex_ao(object, normals, a.rays);
  progress.traced(scene.name, object.triangles.size(), object.positions.size(),
                  seconds_since(start));
  const std::vector<double> traced_used = used_vertex_values(object, traced),
                            traced_ranks = ranks(traced_used);

  struct Row {
    int resolution, viewpoints;
    double seconds;
    std::size_t unseen;
    std::vector<float> map;
  };
  std::vector<Row> rows;
  for (int res : a.resolutions) {
    for (int vp : a.viewpoints) {
      rd::PmiSettings s;
      s.viewpoints = vp, s.width = res, s.height = res * 3 / 4;
      start = std::chrono::steady_clock::now();
      const rd::PmiChannel c = rd::compute_pmi_channel(object, s);
      const std::vector<float> map = rd::vertex_visibility(object, rd::polygon_visibility(c));
      const double t = seconds_since(start);
      const auto unseen = static_cast<std::size_t>(
          std::count(c.polygon_probability.begin(), c.polygon_probability.end(), 0.0));
      rows.push_back({res, vp, t, unseen, map});
      progress.measured(res, s.height, vp, t);
    }
  }
  const std::vector<float>& best = rows.back().map;
  std::string md = fmt::format(
      "| item buffer | viewpoints | time (s) | unseen polygons | Pearson vs ray traced | "
      "Spearman vs ray traced | mean abs diff vs {}x{}/{} |\n| --- | --- | --- | --- | --- | --- | "
      "--- |\n",
      rows.back().resolution, rows.back().resolution * 3 / 4, rows.back().viewpoints);
  for (const Row& r : rows) {
    const std::vector<double> u = used_vertex_values(object, r.map);
    double mad = 0;
    for (std::size_t i = 0; i < best.size(); ++i) mad += std::abs(r.map[i] - best[i]);
    md += fmt::format("| {}x{} | {} | {:.1f} | {} | {:.3f} | {:.3f} | {:.4f} |\n", r.resolution,
                      r.resolution * 3 / 4, r.viewpoints, r.seconds, r.unseen,
                      pearson(u, traced_used), pearson(ranks(u), traced_ranks),
                      mad / static_cast<double>(best.size()));
  }

  // Smoothness per vertex: the paper's setting (162 viewpoints, 1280x960) against the rays.
  const auto paper = std::find_if(rows.begin(), rows.end(), [](const Row& r) {
    return r.resolution == 1280 && r.viewpoints == 162;
  });
  const Row& chosen = paper != rows.end() ? *paper : rows.back();
  md += fmt::format(
      "\n| per vertex | distinct values | mean abs step across an edge | edges with no step |\n"
      "| --- | --- | --- | --- |\n");
  for (const auto& [name, v] : {std::pair{fmt::format("PMI {}x{}/{}", chosen.resolution,
                                                      chosen.resolution * 3 / 4, chosen.viewpoints),
                                          &chosen.map},
                                std::pair{fmt::format("ray traced, {} rays", a.rays), &traced}}) {
    const Smoothness s = vertex_smoothness(object, *v);
    md += fmt::format("| {} | {} | {:.4f} | {:.1f} % |\n", name, s.distinct, s.mean_step,
                      100 * s.flat_edges);
  }

  // Smoothness per pixel, beside the screen-space techniques (each with its default blur;
  // PMI and the ray-traced per-vertex AO unblurred, as the paper shows them).
  const fs::path dir(a.out);
  fs::create_directories(dir);
  const rd::View& view = rd::find_view(scene, a.view);
  md += "\n| rendered AO (" + view.name +
        " view) | distinct 8-bit levels | mean abs step between pixels |\n| --- | --- | --- |\n";
  // The ray-traced per-vertex AO drawn exactly as PMI's map is (per-vertex, unblurred).
  rd::PmiMaps traced_maps;
  traced_maps.object = object, traced_maps.vertex_visibility = traced;
  // PMI, the ray-traced per-vertex AO drawn as PMI's maps are, then every registered
  // screen-space technique.
  std::vector<std::pair<std::string, rd::Technique>> techniques{{"pmi", rd::Technique::kPmi},
                                                                {"raytraced", rd::Technique::kPmi}};
  for (const std::string& name : rd::screen_space_technique_names())
    techniques.emplace_back(name, rd::parse_technique(name));
  for (const auto& [name, t] : techniques) {
    rd::RenderSettings rs;
    rs.width = a.width, rs.height = a.height, rs.technique = t;
    rs.params = rd::default_params(t);
    if (rd::object_space(t)) {
      rs.params.pmi.viewpoints = chosen.viewpoints, rs.params.pmi.resolution = chosen.resolution;
      rs.params.blur = rd::Blur::kNone;
    }
    const bool is_traced = name == "raytraced";
    const rd::Images img = renderer.render(scene, view, rs, is_traced ? &traced_maps : nullptr);
    const Smoothness s = image_smoothness(img);
    md += fmt::format("| {} | {} | {:.4f} |\n",
                      is_traced ? fmt::format("ray traced per vertex, {} rays", a.rays) : name,
                      s.distinct, s.mean_step);
    const std::string stem = fmt::format("{}_{}_{}", scene.name, view.name, name);
    write_png_rgba8(dir / (stem + "_ao_only.png"), img.ao_only);
    if (rd::object_space(t)) write_png_rgba8(dir / (stem + "_with_ao.png"), img.with_ao);
  }
  write_text(dir / "pmi_study.md", md);
  return md;
}

}  // namespace aosuite::ao

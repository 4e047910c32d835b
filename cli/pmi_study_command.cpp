// `aosuite pmi-study`: the PMI paper's Table 1 study (item-buffer resolution x viewpoints:
// time and quality) and its smoothness claim, on one scene's object:
//  - time of each channel (wall clock, llvmpipe);
//  - quality per vertex against ray-traced unbounded AO of the object (Embree, cosine-weighted,
//    `--rays` per vertex): Pearson and Spearman correlation (PMI is normalised differently from
//    AO, so agreement is measured up to a monotone map), and the mean absolute difference from
//    the largest case's map (convergence);
//  - smoothness per vertex (distinct values, differences across mesh edges) and per pixel of
//    the rendered AO (distinct 8-bit levels, mean gradient) beside the screen-space techniques.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <opencv2/core.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cli/commands.hpp"
#include "cli/pmi_vertex_ao.hpp"
#include "compare/opencv.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::cli {
namespace {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;

struct StudyArgs {
  std::string scene = "dragon", view, out = "reports/pmi-study";
  std::vector<int> resolutions{640, 1280, 2560}, viewpoints{12, 42, 162, 642};
  int rays = 256, width = 480, height = 270;
};

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  const double ma = std::accumulate(a.begin(), a.end(), 0.0) / n,
               mb = std::accumulate(b.begin(), b.end(), 0.0) / n;
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    ab += (a[i] - ma) * (b[i] - mb), aa += (a[i] - ma) * (a[i] - ma),
        bb += (b[i] - mb) * (b[i] - mb);
  return aa > 0 && bb > 0 ? ab / std::sqrt(aa * bb) : 0;
}

// Ranks with ties given their mean rank (Spearman's correlation is Pearson's of these).
std::vector<double> ranks(const std::vector<double>& v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return v[a] < v[b]; });
  std::vector<double> r(v.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    for (std::size_t k = i; k <= j; ++k) r[order[k]] = 0.5 * static_cast<double>(i + j);
    i = j + 1;
  }
  return r;
}

// The per-vertex values of the vertices some triangle uses.
std::vector<double> used(const rd::PmiObject& o, const std::vector<float>& v) {
  std::vector<bool> in(o.positions.size(), false);
  for (const glm::uvec3& t : o.triangles) in[t.x] = in[t.y] = in[t.z] = true;
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i)
    if (in[i]) out.push_back(v[i]);
  return out;
}

struct Smoothness {
  std::size_t distinct = 0;
  double mean_step = 0, flat_edges = 0;  // mean |difference| across an edge; share that are 0
};
Smoothness vertex_smoothness(const rd::PmiObject& o, const std::vector<float>& v) {
  Smoothness s;
  const std::vector<double> u = used(o, v);
  s.distinct = std::set<double>(u.begin(), u.end()).size();
  std::size_t edges = 0;
  for (const glm::uvec3& t : o.triangles) {
    for (auto [a, b] : {std::pair{t.x, t.y}, std::pair{t.y, t.z}, std::pair{t.z, t.x}}) {
      const double d = std::abs(v[a] - v[b]);
      s.mean_step += d, s.flat_edges += d == 0, ++edges;
    }
  }
  s.mean_step /= static_cast<double>(edges), s.flat_edges /= static_cast<double>(edges);
  return s;
}

// Over geometry pixels: distinct 8-bit AO levels and the mean |horizontal and vertical step|.
Smoothness image_smoothness(const rd::Images& img) {
  Smoothness s;
  std::set<int> levels;
  double steps = 0;
  for (int y = 0; y + 1 < img.ao.rows; ++y) {
    for (int x = 0; x + 1 < img.ao.cols; ++x) {
      if (img.depth.at<float>(y, x) <= 0) continue;
      const float a = img.ao.at<float>(y, x);
      levels.insert(static_cast<int>(std::lround(a * 255)));
      for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (img.depth.at<float>(y + dy, x + dx) <= 0) continue;
        s.mean_step += std::abs(img.ao.at<float>(y + dy, x + dx) - a), ++steps;
      }
    }
  }
  s.distinct = levels.size();
  s.mean_step /= std::max(1.0, steps);
  return s;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

int run_study(const StudyArgs& a) {
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
  fmt::print("{}: {} polygons, {} vertices; ray-traced AO ({} rays per vertex) in {:.1f} s\n",
             scene.name, object.triangles.size(), object.positions.size(), a.rays,
             seconds_since(start));
  const std::vector<double> traced_used = used(object, traced), traced_ranks = ranks(traced_used);

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
      fmt::print(stderr, "{}x{} {} viewpoints: {:.1f} s\n", res, s.height, vp, t);
    }
  }
  const std::vector<float>& best = rows.back().map;
  std::string md = fmt::format(
      "| item buffer | viewpoints | time (s) | unseen polygons | Pearson vs ray traced | "
      "Spearman vs ray traced | mean abs diff vs {}x{}/{} |\n| --- | --- | --- | --- | --- | --- | "
      "--- |\n",
      rows.back().resolution, rows.back().resolution * 3 / 4, rows.back().viewpoints);
  for (const Row& r : rows) {
    const std::vector<double> u = used(object, r.map);
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
  fmt::print("{}", md);
  return kExitSame;
}

}  // namespace

void add_pmi_study_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<StudyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "pmi-study", "PMI's resolution x viewpoints study: time, agreement with ray-traced AO");
  cmd->add_option("--scene", a->scene, "built-in scene or scene file")->capture_default_str();
  cmd->add_option("--view", a->view, "view for the rendered comparison (default: the first)");
  cmd->add_option("--resolutions", a->resolutions, "item-buffer widths")->delimiter(',');
  cmd->add_option("--viewpoints", a->viewpoints, "viewpoint counts")->delimiter(',');
  cmd->add_option("--rays", a->rays, "rays per vertex of the ray-traced AO")->capture_default_str();
  cmd->add_option("--width", a->width, "rendered comparison width")->capture_default_str();
  cmd->add_option("--height", a->height, "rendered comparison height")->capture_default_str();
  cmd->add_option("--out", a->out)->capture_default_str();
  guarded(cmd, rc, "pmi-study", [a] { return run_study(*a); });
}

}  // namespace aosuite::cli

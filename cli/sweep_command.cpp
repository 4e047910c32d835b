// `aosuite sweep GRID.toml`: every technique over its samples x radius (x intensity) grid on
// the grid's scenes, views and resolutions; per configuration the median AO time (all passes
// but the G-buffer's and the blend's) and the error against the ray-traced reference at the
// technique's radius (and against the unbounded reference). Writes sweep.csv, sweep.json
// (rows and the fit-on-one-view result), sweep.md (both as tables) and time-vs-RMSE SVGs per
// resolution (against the radius-r and the unbounded reference).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <tuple>

#include "cli/commands.hpp"
#include "cli/gl_command_util.hpp"
#include "cli/sweep_grid.hpp"
#include "cli/sweep_plot.hpp"
#include "cli/sweep_rows.hpp"
#include "compare/image_io.hpp"
#include "harness/runner.hpp"
#include "reference/reference_cache.hpp"
#include "renderer/params.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::cli {
namespace {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;
namespace ref = aosuite::reference;

// The grid's fixed parameters as text: "blur=none level_weights=1,0,0,0,0".
std::string params_text(const Row& r) {
  std::string out;
  for (const auto& [k, v] : r.params) out += (out.empty() ? "" : " ") + k + "=" + v;
  return out;
}

// The technique as the console and Markdown name it: "mssao (max_pixel_radius=10)".
std::string label(const Row& r) {
  const std::string name(rd::technique_name(r.technique));
  return r.params.empty() ? name : fmt::format("{} ({})", name, params_text(r));
}

struct Timed {
  rd::Images images;
  double gl_ms;
};

// One warm-up frame (llvmpipe compiles shader variants on first use), then the median over
// `runs` frames of the AO work: every pass except the G-buffer and the blend.
Timed render_timed(rd::Renderer& renderer, const rd::Scene& scene, const rd::View& view,
                   const rd::RenderSettings& s, int runs) {
  renderer.render(scene, view, s);
  std::vector<double> gl;
  Timed t{{}, 0};
  for (int r = 0; r < runs; ++r) {
    t.images = renderer.render(scene, view, s);
    double g = 0;
    for (const rd::PassTime& p : t.images.times) {
      if (p.pass != "gbuffer" && p.pass != "blend") g += p.gpu_ms;
    }
    gl.push_back(g);
  }
  t.gl_ms = median(gl);
  return t;
}

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
                std::size_t view_index, int w, int h, std::size_t& index, std::vector<Row>& rows) {
  const rd::Camera camera = rd::make_camera(view, w, h);
  std::optional<rd::Images> gbuffer;
  auto reference = [&](const ref::ReferenceSettings& rs) {
    if (!gbuffer) {
      rd::RenderSettings gs;
      gs.width = w, gs.height = h;
      gs.outputs = rd::Outputs{false, false, false, false};
      gs.outputs.normal = true;
      gbuffer = renderer.render(scene, view, gs);
    }
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
                  ref::measure_error(t.images.ao, at_radius, t.images.depth, metric),
                  {},
                  {},
                  tg.params};
          if (g.unbounded)
            row.unbounded = ref::measure_error(t.images.ao, unbounded, t.images.depth, metric).all;
          row.frame = ref::frame_error(t.images.no_ao, t.images.ao, at_radius, t.images.depth);
          fmt::print("{} {} {}x{} {} s={} r={:g} k={:g}: {:.1f} ms, RMSE {:.4f}{}\n", row.scene,
                     row.view, w, h, label(row), samples, radius, intensity, row.gl_ms,
                     row.error.all.rmse,
                     g.unbounded ? fmt::format(" (unbounded {:.4f})", row.unbounded.rmse) : "");
          std::fflush(stdout);
          rows.push_back(std::move(row));
        }
      }
    }
  }
}

std::string csv(const std::vector<Row>& rows, bool unbounded) {
  std::string out =
      "scene,view,technique,width,height,samples,radius,intensity,ao_gl_ms,pixels,rmse,"
      "mae,bias,psnr,ssim,noise_floor,edge_rmse,interior_rmse,rmse_unbounded,bias_unbounded,"
      "ssim_unbounded,";
  for (const metric::Metric* m : metric::all()) out += fmt::format("frame_{},", m->name);
  out += "params\n";
  for (const Row& r : rows) {
    const ref::ErrorStats& a = r.error.all;
    out += fmt::format(
        "{},{},{},{},{},{},{:g},{:g},{:.3f},{},{:.6f},{:.6f},{:.6f},{:.4f},{:.6f},{:.6f},{:."
        "6f},{:.6f}",
        r.scene, r.view, rd::technique_name(r.technique), r.width, r.height, r.samples, r.radius,
        r.intensity, r.gl_ms, a.pixels, a.rmse, a.mae, a.bias, a.psnr, a.ssim, a.noise_floor,
        r.error.edge.rmse, r.error.interior.rmse);
    out += unbounded ? fmt::format(",{:.6f},{:.6f},{:.6f}", r.unbounded.rmse, r.unbounded.bias,
                                   r.unbounded.ssim)
                     : ",,,";
    for (const metric::Value& v : r.frame.values)  // an infinite PSNR (no difference): empty
      out += std::isfinite(v.value) ? fmt::format(",{:.6f}", v.value) : std::string(",");
    // Quoted: list values hold commas.
    out += r.params.empty() ? ",\n" : fmt::format(",\"{}\"\n", params_text(r));
  }
  return out;
}

// The rows and the fit as Markdown tables, for docs/results.md.
std::string markdown(const std::vector<Row>& rows, const nlohmann::ordered_json& fit,
                     bool unbounded) {
  std::string md =
      "| scene | view | technique | size | s | r | k | AO ms | RMSE | noise | bias | SSIM | edge "
      "RMSE "
      "| interior RMSE | RMSE unbounded | frame FLIP | frame SSIM "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";  // the CSV has
                                                                                     // every metric
  for (const Row& r : rows) {
    const ref::ErrorStats& a = r.error.all;
    md += fmt::format(
        "| {} | {} | {} | {}×{} | {} | {:g} | {:g} | {:.1f} | {:.4f} | {:.4f} | {:+.4f} | "
        "{:.3f} | {:.4f} | {:.4f} | {} | {:.4f} | {:.4f} |\n",
        r.scene, r.view, label(r), r.width, r.height, r.samples, r.radius, r.intensity, r.gl_ms,
        a.rmse, a.noise_floor, a.bias, a.ssim, r.error.edge.rmse, r.error.interior.rmse,
        unbounded ? fmt::format("{:.4f}", r.unbounded.rmse) : "–", r.frame.value("flip"),
        r.frame.value("ssim"));
  }
  md +=
      "\n| scene | technique | size | fitted on | s | r | k | RMSE there | evaluated on | RMSE "
      "there | best RMSE there |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& f : fit) {
    md +=
        fmt::format("| {} | {} | {}×{} | {} | {} | {:g} | {:g} | {:.4f} | {} | {:.4f} | {:.4f} |\n",
                    f["scene"].get<std::string>(), f["technique"].get<std::string>(),
                    f["width"].get<int>(), f["height"].get<int>(), f["fit_view"].get<std::string>(),
                    f["samples"].get<int>(), f["radius"].get<float>(), f["intensity"].get<float>(),
                    f["rmse_fit_view"].get<double>(), f["eval_view"].get<std::string>(),
                    f["rmse_eval_view"].get<double>(), f["best_rmse_eval_view"].get<double>());
  }
  return md;
}

// For each scene, technique and resolution: the configuration with the lowest RMSE on the
// first view, and its RMSE on the second (beside the second view's own best).
nlohmann::ordered_json fit_on_one_view(const std::vector<Row>& rows) {
  using Group = std::tuple<std::string, rd::Technique, int, int>;
  std::map<Group, const Row*> best_fit, best_eval;
  for (const Row& r : rows) {
    const Group key{r.scene, r.technique, r.width, r.height};
    auto& slot = r.view_index == 0 ? best_fit[key] : best_eval[key];
    if (r.view_index <= 1 && (!slot || r.error.all.rmse < slot->error.all.rmse)) slot = &r;
  }
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& [key, fit] : best_fit) {
    const Row* eval = nullptr;
    for (const Row& r : rows) {
      if (r.view_index == 1 && r.scene == fit->scene && r.technique == fit->technique &&
          r.width == fit->width && r.height == fit->height && r.samples == fit->samples &&
          r.radius == fit->radius && r.intensity == fit->intensity)
        eval = &r;
    }
    if (!eval) continue;  // a scene with one view has nothing to evaluate on
    out.push_back({{"scene", fit->scene},
                   {"technique", rd::technique_name(fit->technique)},
                   {"width", fit->width},
                   {"height", fit->height},
                   {"fit_view", fit->view},
                   {"eval_view", eval->view},
                   {"samples", fit->samples},
                   {"radius", fit->radius},
                   {"intensity", fit->intensity},
                   {"rmse_fit_view", fit->error.all.rmse},
                   {"rmse_eval_view", eval->error.all.rmse},
                   {"best_rmse_eval_view", best_eval.at(key)->error.all.rmse}});
  }
  return out;
}

// One plot per resolution: each configuration's mean time and mean RMSE over scenes and views,
// against the reference at the technique's radius or (`unbounded`) against unbounded rays,
// the yardstick common to all radii.
void write_plots(const std::vector<Row>& rows, const fs::path& dir, const std::string& name,
                 bool unbounded) {
  using Config = std::tuple<rd::Technique, int, float, float>;
  std::map<std::pair<int, int>, std::map<Config, std::tuple<double, double, int>>> sums;
  for (const Row& r : rows) {
    auto& [t, e, n] = sums[{r.width, r.height}][{r.technique, r.samples, r.radius, r.intensity}];
    t += r.gl_ms, e += unbounded ? r.unbounded.rmse : r.error.all.rmse, ++n;
  }
  for (const auto& [res, configs] : sums) {
    std::vector<PlotPoint> points;
    for (const auto& [c, s] : configs) {
      const auto& [t, e, n] = s;
      const auto [tech, samples, radius, intensity] = c;
      points.push_back(
          {std::string(rd::technique_name(tech)), std::max(t / n, 1e-3), e / n,
           fmt::format("{} s={} r={:g} k={:g}: {:.1f} ms, RMSE {:.4f}", rd::technique_name(tech),
                       samples, radius, intensity, t / n, e / n)});
    }
    const std::string svg = pareto_svg(
        points,
        fmt::format("{}: AO time vs RMSE at {}x{} (mean over scenes and views)", name, res.first,
                    res.second),
        "AO passes, median GPU ms (log scale)",
        unbounded ? "RMSE vs ray-traced AO (unbounded)" : "RMSE vs ray-traced AO (radius r)");
    write_text(dir / fmt::format("sweep_{}x{}{}.svg", res.first, res.second,
                                 unbounded ? "_unbounded" : ""),
               svg);
  }
}

// "1280x720" -> {1280, 720}; throws std::invalid_argument otherwise.
std::pair<int, int> parse_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 16 ||
      h < 16 || w > 8192 || h > 8192) {
    throw std::invalid_argument("--resolution '" + text + "': expected WxH, sides 16..8192");
  }
  return {w, h};
}

// What every shard of one sweep shares, and a merge checks.
struct SweepMeta {
  std::string grid, gl, gl_device;
  int rays = 0, runs = 0;
  bool unbounded = false;
  std::size_t configurations = 0;  // in the whole grid, every shard's rows together
};

nlohmann::ordered_json meta_json(const SweepMeta& m) {
  return {{"grid", m.grid},
          {"rays", m.rays},
          {"runs", m.runs},
          {"gl", m.gl},
          {"gl_device", m.gl_device},
          {"unbounded", m.unbounded},
          {"configurations", m.configurations}};
}

void write_sweep(const fs::path& dir, const SweepMeta& m, const std::vector<Row>& rows,
                 const std::string& shard) {
  fs::create_directories(dir);
  write_text(dir / "sweep.csv", csv(rows, m.unbounded));
  nlohmann::ordered_json j = meta_json(m);
  if (!shard.empty()) j["shard"] = shard;
  j["rows"] = nlohmann::ordered_json::array();
  for (const Row& r : rows) j["rows"].push_back(row_json(r, m.unbounded));
  j["fit_on_one_view"] = fit_on_one_view(rows);
  write_text(dir / "sweep.json", j.dump(2) + "\n");
  write_text(dir / "sweep.md", markdown(rows, j["fit_on_one_view"], m.unbounded));
  write_plots(rows, dir, m.grid, false);
  if (m.unbounded) write_plots(rows, dir, m.grid, true);
  fmt::print("fit on the first view, evaluated on the second:\n");
  for (const auto& f : j["fit_on_one_view"]) {
    fmt::print("  {} {} {}x{}: s={} r={} k={} RMSE {:.4f} on {}, {:.4f} on {} (its best {:.4f})\n",
               f["scene"].get<std::string>(), f["technique"].get<std::string>(),
               f["width"].get<int>(), f["height"].get<int>(), f["samples"].get<int>(),
               f["radius"].get<float>(), f["intensity"].get<float>(),
               f["rmse_fit_view"].get<double>(), f["fit_view"].get<std::string>(),
               f["rmse_eval_view"].get<double>(), f["eval_view"].get<std::string>(),
               f["best_rmse_eval_view"].get<double>());
  }
  fmt::print("{} rows: {}\n", rows.size(), (dir / "sweep.csv").string());
}

int run_sweep(const std::string& grid_file, const std::vector<std::string>& resolutions,
              const std::vector<std::string>& scenes, const std::string& shard_text,
              const std::string& out) {
  SweepGrid g = read_sweep_grid(grid_file);
  if (!scenes.empty()) g.scenes = scenes;
  if (!resolutions.empty()) {
    g.resolutions.clear();
    for (const std::string& r : resolutions) g.resolutions.push_back(parse_size(r));
  }
  harness::Selection shard;
  if (!shard_text.empty()) harness::set_shard(shard, shard_text);
  rd::Renderer renderer;
  std::vector<Row> rows;
  std::size_t index = 0;
  for (const std::string& name : g.scenes) {
    const rd::Scene scene = rd::load_scene(name);
    const std::vector<const rd::View*> views = pick_views(scene, g.views);
    ref::ReferenceCache cache(scene, ref::default_cache_dir());
    for (const auto& [w, h] : g.resolutions) {
      for (std::size_t v = 0; v < views.size(); ++v)
        sweep_view(renderer, g, shard, scene, cache, *views[v], v, w, h, index, rows);
    }
  }
  const SweepMeta m{
      g.name, renderer.gl_description(), renderer.gl_source(), g.rays, g.runs, g.unbounded, index};
  write_sweep(out, m, rows,
              shard_text.empty() ? "" : fmt::format("{}/{}", shard.shard_index, shard.shard_count));
  return kExitSame;
}

// The shards' rows in the grid's order, written as one run writes them. Refuses shards of
// different grids or devices, a configuration twice, and a grid with configurations missing.
int merge_sweeps(const std::vector<std::string>& shard_dirs, const std::string& out) {
  std::optional<SweepMeta> meta;
  std::map<std::size_t, Row> by_index;
  for (const std::string& d : shard_dirs) {
    const fs::path file = fs::path(d) / "sweep.json";
    SweepMeta m;
    std::vector<Row> rows;
    try {
      const std::vector<unsigned char> bytes = read_file(file);
      const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end());
      m = {j.at("grid"), j.at("gl"),        j.at("gl_device"),     j.at("rays"),
           j.at("runs"), j.at("unbounded"), j.at("configurations")};
      for (const nlohmann::json& r : j.at("rows")) rows.push_back(row_from_json(r));
    } catch (const FileError&) {
      throw;
    } catch (const std::exception& e) {
      throw FileError(file.string() + ": not a sweep.json: " + e.what());
    }
    if (!meta) meta = m;
    if (meta_json(m) != meta_json(*meta)) {
      throw FileError(file.string() + ": another grid, its settings or GL device than " +
                      (fs::path(shard_dirs.front()) / "sweep.json").string());
    }
    for (Row& r : rows) {
      const std::size_t i = r.index;
      if (i >= m.configurations || !by_index.emplace(i, std::move(r)).second) {
        throw FileError(
            fmt::format("{}: configuration {} is out of range or in two shards", file.string(), i));
      }
    }
  }
  if (!meta || by_index.size() != meta->configurations) {
    throw std::invalid_argument(fmt::format("the shards hold {} of the grid's {} configurations",
                                            by_index.size(), meta ? meta->configurations : 0));
  }
  std::vector<Row> rows;
  for (auto& [i, r] : by_index) rows.push_back(std::move(r));
  write_sweep(out, *meta, rows, "");
  return kExitSame;
}

}  // namespace

void add_sweep_command(CLI::App& app, int& rc) {
  struct Args {
    std::string grid, out = "reports/sweep", shard;
    std::vector<std::string> resolutions, scenes, merge;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Time and error of each technique over a samples x radius x resolution grid");
  cmd->add_option("grid", a->grid, "grid file (suites/sweep_ci.toml, suites/sweep_full.toml)");
  cmd->add_option("--out", a->out, "output directory")->capture_default_str();
  cmd->add_option("--resolution", a->resolutions,
                  "WxH, repeatable: replaces the grid's resolutions");
  cmd->add_option("--scene", a->scenes,
                  "scene name or file, repeatable: replaces the grid's scenes");
  cmd->add_option("--shard", a->shard,
                  "i/n: run every n-th configuration from the i-th (0-based; default: "
                  "GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS when set); merge with --merge");
  cmd->add_option("--merge", a->merge,
                  "shard output folder, repeatable: merge the shards' rows into --out as one "
                  "run writes them (no grid, nothing rendered)");
  guarded(cmd, rc, "sweep", [a] {
    if (!a->merge.empty()) {
      if (!a->grid.empty() || !a->shard.empty() || !a->resolutions.empty() || !a->scenes.empty())
        throw std::invalid_argument("--merge takes only shard folders and --out");
      return merge_sweeps(a->merge, a->out);
    }
    if (a->grid.empty()) throw std::invalid_argument("a grid file is required (or --merge)");
    return run_sweep(a->grid, a->resolutions, a->scenes, a->shard, a->out);
  });
}

}  // namespace aosuite::cli

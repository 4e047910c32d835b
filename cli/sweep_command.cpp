// `aosuite sweep GRID.toml`: every technique over its samples x radius (x intensity) grid on
// the grid's scenes, views and resolutions (ao/sweep_run.hpp), or `--merge` of a sharded
// sweep's folders (ao/sweep_merge.hpp). Writes sweep.csv, sweep.json, sweep.md and
// time-vs-RMSE SVGs per resolution (ao/sweep_report.hpp).
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <utility>

#include "ao/preset.hpp"
#include "ao/sweep_merge.hpp"
#include "ao/sweep_report.hpp"
#include "ao/sweep_run.hpp"
#include "cli/commands.hpp"
#include "cli/gl_command_util.hpp"
#include "harness/runner.hpp"
#include "image/image_io.hpp"

namespace aosuite::cli {
namespace {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;

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

void write_sweep(const fs::path& dir, const ao::SweepResult& sweep, const std::string& shard) {
  const ao::SweepReport report = ao::sweep_report(sweep, shard);
  fs::create_directories(dir);
  for (const ao::SweepFile& f : report.files) write_text(dir / f.name, f.text);
  fmt::print("fit on the first view, evaluated on the second:\n");
  for (const auto& f : report.fit) {
    fmt::print("  {} {} {}x{}: s={} r={} k={} RMSE {:.4f} on {}, {:.4f} on {} (its best {:.4f})\n",
               f["scene"].get<std::string>(), f["technique"].get<std::string>(),
               f["width"].get<int>(), f["height"].get<int>(), f["samples"].get<int>(),
               f["radius"].get<float>(), f["intensity"].get<float>(),
               f["rmse_fit_view"].get<double>(), f["fit_view"].get<std::string>(),
               f["rmse_eval_view"].get<double>(), f["eval_view"].get<std::string>(),
               f["best_rmse_eval_view"].get<double>());
  }
  // Every file it wrote, the plots included: where to look next.
  std::string files;
  for (const ao::SweepFile& f : report.files) files += (files.empty() ? "" : ", ") + f.name;
  fmt::print("{} rows in {}: {}\n", sweep.rows.size(), dir.string(), files);
}

struct SweepArgs {
  std::string grid, out = "reports/sweep", shard, preset;
  std::vector<std::string> resolutions, scenes, merge;
  std::string pipeline;
};

int run_sweep(const SweepArgs& a) {
  // A preset file on the command line is the current directory's, not the grid's.
  const std::string preset =
      ao::is_preset_file(a.preset) ? std::filesystem::absolute(a.preset).string() : a.preset;
  ao::SweepGrid g = ao::read_sweep_grid(a.grid, preset);
  if (!a.scenes.empty()) g.scenes = a.scenes;
  if (!a.pipeline.empty()) g.pipeline = rd::parse_pipeline(a.pipeline);
  if (!a.resolutions.empty()) {
    g.resolutions.clear();
    for (const std::string& r : a.resolutions) g.resolutions.push_back(parse_size(r));
  }
  harness::Selection shard;
  if (!a.shard.empty()) harness::set_shard(shard, a.shard);
  std::set<std::pair<std::string, std::string>> empty_views;  // warned once each
  const ao::SweepResult sweep = ao::run_sweep(g, shard, [&](const ao::Row& row) {
    if (row.geometry_pixels == 0 && empty_views.emplace(row.scene, row.view).second) {
      fmt::print(stderr,
                 "aosuite sweep: warning: view '{}' of {} draws no geometry (everything clipped "
                 "or background): its rows measure only the background\n",
                 row.view, row.scene);
    }
    fmt::print("{} {} {}x{} {} s={} r={:g} k={:g}: {:.1f} ms, RMSE {:.4f}{}\n", row.scene, row.view,
               row.width, row.height, ao::row_label(row), row.samples, row.radius, row.intensity,
               row.gl_ms, row.error.all.rmse,
               g.unbounded ? fmt::format(" (unbounded {:.4f})", row.unbounded.rmse) : "");
    std::fflush(stdout);
  });
  write_sweep(a.out, sweep,
              a.shard.empty() ? "" : fmt::format("{}/{}", shard.shard_index, shard.shard_count));
  return kExitSame;
}

}  // namespace

void add_sweep_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Time and error of each technique over a samples x radius x resolution grid");
  cmd->add_option("grid", a->grid, "grid file (suites/sweep_ci.toml, suites/sweep_full.toml)");
  cmd->add_option("--out", a->out, "output directory")->capture_default_str();
  add_pipeline_option(cmd, a->pipeline);
  cmd->add_option("--resolution", a->resolutions,
                  "WxH, repeatable: replaces the grid's resolutions");
  cmd->add_option("--scene", a->scenes,
                  "scene name or file, repeatable: replaces the grid's scenes");
  cmd->add_option("--preset", a->preset,
                  "a preset file or built-in name (tuned) for every technique table without its "
                  "own preset");
  cmd->add_option("--shard", a->shard,
                  "i/n: run every n-th configuration from the i-th (0-based; default: "
                  "GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS when set); merge with --merge");
  cmd->add_option("--merge", a->merge,
                  "shard output folder, repeatable: merge the shards' rows into --out as one run "
                  "writes them (no grid, nothing rendered)");
  guarded(cmd, rc, "sweep", [a] {
    if (!a->merge.empty()) {
      if (!a->grid.empty() || !a->shard.empty() || !a->resolutions.empty() || !a->scenes.empty() ||
          !a->preset.empty())
        throw std::invalid_argument("--merge takes only shard folders and --out");
      write_sweep(a->out, ao::merge_sweeps(a->merge), "");
      return kExitSame;
    }
    if (a->grid.empty()) throw std::invalid_argument("a grid file is required (or --merge)");
    return run_sweep(*a);
  });
}

}  // namespace aosuite::cli

// `aosuite tune`: searches one technique's parameters against the ray-traced reference
// (ao/tune_run.hpp), prints each held-out scene's error under the defaults and tuned, and
// writes the preset searched on every scene, with the command that made it.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "ao/preset.hpp"
#include "ao/tune_run.hpp"
#include "cli/commands.hpp"
#include "cli/gl_command_util.hpp"
#include "common/file_io.hpp"
#include "harness/invocation.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::cli {
namespace {

namespace rd = aosuite::renderer;

struct TuneArgs {
  std::string technique, out, json;
  std::vector<std::string> scenes;
  std::string state;  // default: beside --out
  std::string pipeline;
  ao::TuneSettings s;
};

// The command that makes the same preset, for its header.
std::string command_line(const TuneArgs& a) {
  std::string radii;
  for (float r : a.s.radii) radii += fmt::format(" --radius {:g}", r);
  return fmt::format(
      "{} tune --technique {}{} --scenes {} --width {} --height {} --rays {} --trials {} "
      "--seed {} --budget-taps {} --max-worse-share {:g} --max-worse-ratio {:g}",
      harness::program_command(), a.technique, radii, fmt::join(a.s.scenes, ","), a.s.width,
      a.s.height, a.s.rays, a.s.search.trials, a.s.search.seed, a.s.search.budget_taps,
      a.s.bar.worse_share, a.s.bar.worst_ratio);
}

struct Spread {
  double mean = 0, sd = 0;
};

Spread spread(const std::vector<double>& v) {
  Spread s;
  for (double x : v) s.mean += x / static_cast<double>(v.size());
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(s.sd / static_cast<double>(v.size() - 1)) : 0;
  return s;
}

// Per radius: the held-out error of every fold, under the defaults and tuned.
std::vector<double> column(const std::vector<ao::Fold>& folds, std::size_t k, bool tuned) {
  std::vector<double> out;
  for (const ao::Fold& f : folds) out.push_back(tuned ? f.tuned_error[k] : f.default_error[k]);
  return out;
}

std::string radii_text(const std::vector<float>& radii) {
  std::string out;
  for (float r : radii) out += (out.empty() ? "" : ", ") + fmt::format("{:g}", r);
  return out;
}

// Every held-out scene's tuned/default error ratio: how many got worse, and the worst.
struct HeldOutRatios {
  int count = 0, worse = 0;
  double worst = 0;
  std::string worst_scene;
};

HeldOutRatios held_out_ratios(const std::vector<ao::Fold>& folds) {
  HeldOutRatios out;
  for (const ao::Fold& f : folds) {
    for (const ao::HeldOutScene& h : f.scenes) {
      const double ratio = ao::error_ratio(h.tuned_error, h.default_error);
      ++out.count, out.worse += ratio > 1;
      if (ratio > out.worst) out.worst = ratio, out.worst_scene = h.scene;
    }
  }
  return out;
}

// Why the preset is what it is, for its header and the terminal: the shrinks tried on the
// folds' held-out (scene, radius) pairs and the one chosen. Empty without folds.
std::string shrink_text(const TuneArgs& a, const ao::TuneResult& r) {
  if (r.shrink_trials.empty()) return {};
  const ao::TuneSpace space(a.s.technique);
  std::string tried;
  for (const ao::ShrinkTrial& t : r.shrink_trials)
    tried += fmt::format("{}{:g}: mean {:.3f} (log ±{:.3f}), worst {:.3f}, {} of {} worse{}",
                         tried.empty() ? "" : "; ", t.shrink, t.mean_ratio, t.log_se, t.worst_ratio,
                         t.worse, t.pairs,
                         !t.within_bar      ? " (over the bar)"
                         : !t.within_budget ? " (over the depth-tap budget)"
                                            : "");
  const std::string chosen =
      r.shrink == 0
          ? "the defaults kept: no share within the bar beat them by more than its standard error"
      : space.key(r.searched) == space.key(r.defaults)
          ? fmt::format(
                "share {:g}, but the search on every scene found nothing better than "
                "the defaults: the preset is the defaults",
                r.shrink)
          : fmt::format("the search's parameters moved {:g} of the way from the defaults",
                        r.shrink);
  return fmt::format(
      "Chosen on held-out pairs (each family left out in turn, its (scene, radius) pairs' error "
      "over the defaults'), by the share of the way from the defaults to each fold's search, "
      "within the bar of at most {:g} % of pairs worse and none by over {:g} %: {}. The "
      "smallest share within the bar and within one standard error of the best mean is chosen. "
      "So {}.",
      100 * a.s.bar.worse_share, 100 * (a.s.bar.worst_ratio - 1), tried, chosen);
}

nlohmann::ordered_json result_json(const TuneArgs& a, const ao::TuneResult& r) {
  const ao::TuneSpace space(a.s.technique);
  nlohmann::ordered_json j;
  j["technique"] = a.technique, j["radii"] = a.s.radii, j["scenes"] = a.s.scenes;
  j["width"] = a.s.width, j["height"] = a.s.height, j["rays"] = a.s.rays;
  j["trials"] = a.s.search.trials, j["seed"] = a.s.search.seed;
  j["budget_taps"] = a.s.search.budget_taps;
  j["preset"] = space.key(r.tuned), j["default"] = space.key(r.defaults);
  j["searched"] = space.key(r.searched);
  nlohmann::ordered_json trials = nlohmann::ordered_json::array();
  for (const ao::ShrinkTrial& t : r.shrink_trials)
    trials.push_back({{"shrink", t.shrink},
                      {"pairs", t.pairs},
                      {"worse", t.worse},
                      {"worst_ratio", t.worst_ratio},
                      {"mean_ratio", t.mean_ratio},
                      {"log_se", t.log_se},
                      {"fold_ratio", t.fold_ratio},
                      {"fold_error", t.fold_error},
                      {"within_bar", t.within_bar},
                      {"within_budget", t.within_budget}});
  j["shrink"] = {
      {"chosen", r.shrink},
      {"bar", {{"worse_share", a.s.bar.worse_share}, {"worst_ratio", a.s.bar.worst_ratio}}},
      {"trials", trials}};
  j["error"] = {{"tuned", r.tuned_error}, {"default", r.default_error}};
  j["taps"] = {{"tuned", r.tuned_taps}, {"default", r.default_taps}};
  j["ao_ms"] = {{"tuned", r.tuned_ms}, {"default", r.default_ms}, {"view", r.timed_view}};
  nlohmann::ordered_json folds = nlohmann::ordered_json::array();
  for (const ao::Fold& f : r.folds) {
    nlohmann::ordered_json scenes = nlohmann::ordered_json::array();
    for (const ao::HeldOutScene& h : f.scenes) {
      scenes.push_back({{"scene", h.scene},
                        {"default", h.default_error},
                        {"tuned", h.tuned_error},
                        {"ratio", ao::error_ratio(h.tuned_error, h.default_error)}});
    }
    folds.push_back({{"held_out", f.held_out},
                     {"default", f.default_error},
                     {"tuned", f.tuned_error},
                     {"params", f.params},
                     {"scenes", scenes}});
  }
  j["folds"] = folds;
  const HeldOutRatios ratios = held_out_ratios(r.folds);
  j["held_out_scenes"] = {{"count", ratios.count},
                          {"worse", ratios.worse},
                          {"worst_ratio", ratios.worst},
                          {"worst_scene", ratios.worst_scene}};
  j["left_out"] = r.left_out;
  return j;
}

// Whether the technique's cost is depth taps (screen space); PMI's is its precomputed channel.
bool taps(rd::Technique t) { return !rd::object_space(t); }

void print_result(const TuneArgs& a, const ao::TuneResult& r) {
  const ao::TuneSpace space(a.s.technique);
  fmt::print(
      "{} at r = {} on {} ({}x{}, reference {} rays){}\n", a.technique, radii_text(a.s.radii),
      fmt::join(a.s.scenes, ", "), a.s.width, a.s.height, a.s.rays,
      taps(a.s.technique) ? fmt::format(", at most {} depth taps", a.s.search.budget_taps) : "");
  for (const std::string& v : r.left_out) fmt::print("  left out {}\n", v);
  if (!r.folds.empty()) {
    fmt::print(
        "AO RMSE on the family left out (each scene, when all are of one family), "
        "searched on the others:\n");
    fmt::print("  {:<14} {:>6} {:>9} {:>9}\n", "held out", "r", "default", "tuned");
    for (const ao::Fold& f : r.folds) {
      for (std::size_t k = 0; k < a.s.radii.size(); ++k)
        fmt::print("  {:<14} {:>6g} {:>9.4f} {:>9.4f}\n", f.held_out, a.s.radii[k],
                   f.default_error[k], f.tuned_error[k]);
    }
    for (std::size_t k = 0; k < a.s.radii.size(); ++k) {
      const Spread d = spread(column(r.folds, k, false)), t = spread(column(r.folds, k, true));
      fmt::print(
          "  r = {:g}: default {:.4f} ± {:.4f}, tuned {:.4f} ± {:.4f} ({:+.1f} %), mean ± sd "
          "over {} folds\n",
          a.s.radii[k], d.mean, d.sd, t.mean, t.sd, 100 * (t.mean / d.mean - 1), r.folds.size());
    }
    const HeldOutRatios ratios = held_out_ratios(r.folds);
    fmt::print("  each scene left out, tuned / default: worst {:.3f} ({}), {} of {} worse\n",
               ratios.worst, ratios.worst_scene, ratios.worse, ratios.count);
  }
  if (const std::string why = shrink_text(a, r); !why.empty()) fmt::print("{}\n", why);
  fmt::print("preset, searched on every scene: {}\n  {}\n", a.out, space.key(r.tuned));
  const std::string cost = taps(a.s.technique) ? fmt::format("; {} depth taps (defaults {})",
                                                             r.tuned_taps, r.default_taps)
                                               : "";
  fmt::print(
      "  AO RMSE {:.4f} (defaults {:.4f}){}; AO {:.2f} ms a frame of {} at {}x{} (defaults "
      "{:.2f} ms)\n",
      r.tuned_error, r.default_error, cost, r.tuned_ms, r.timed_view, a.s.width, a.s.height,
      r.default_ms);
  fmt::print("measurements: {} rendered, {} reused from {}\n", r.renders, r.reused, a.state);
}

// The built-in scenes, the downloadable ones that are here (the dragon), and the scene files
// of ./suites/scenes (the project's: meshes that scripts/fetch_assets.sh fetches) that load; one
// line on stderr for each left out.
std::vector<std::string> default_scenes() {
  std::vector<std::string> out = rd::builtin_scene_names();
  for (const std::string& name : rd::downloadable_scene_names()) {
    if (std::filesystem::exists(rd::downloadable_scene_file(name))) out.push_back(name);
  }
  const std::filesystem::path dir = "suites/scenes";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return out;
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().extension() == ".toml") files.push_back(entry.path().generic_string());
  std::ranges::sort(files);
  for (const std::string& file : files) {
    try {
      rd::load_scene_file(file);
      out.push_back(file);
    } catch (const std::exception& e) {
      fmt::print(stderr, "aosuite tune: left out {}\n", printable(e.what()));
    }
  }
  return out;
}

int run_tune(TuneArgs& a) {
  a.s.technique = rd::parse_technique(a.technique);
  a.s.scenes = a.scenes.empty() ? default_scenes() : a.scenes;
  if (a.out.empty()) a.out = fmt::format("reports/tune/{}.toml", a.technique);
  if (a.state.empty()) a.state = a.out + ".state.json";
  a.s.state = a.state;
  if (!a.pipeline.empty()) a.s.pipeline = rd::parse_pipeline(a.pipeline);
  const bool tty = isatty(fileno(stderr));
  const ao::TuneResult r = ao::run_tune(a.s, [&](const ao::TuneProgress& p) {
    // One line per stage on a pipe; the running best in place on a terminal.
    if (tty || p.done)
      fmt::print(stderr, "{}{}: trial {}/{}, best error over the defaults' {:.4f}{}",
                 tty ? "\r" : "", p.stage, p.trial, p.trials, p.best, p.done ? "\n" : "");
  });
  const ao::TuneSpace space(a.s.technique);
  ao::Preset preset{a.out, a.s.technique, space.entries(r.tuned)};
  std::vector<std::string> header = {
      fmt::format("Made by `{}`.", command_line(a)),
      fmt::format("AO RMSE {:.4f} against the ray-traced reference on {} (defaults {:.4f}).",
                  r.tuned_error, fmt::join(r.scenes, ", "), r.default_error)};
  if (taps(a.s.technique))
    header.push_back(
        fmt::format("{} depth taps per pixel (defaults {}).", r.tuned_taps, r.default_taps));
  if (const std::string why = shrink_text(a, r); !why.empty()) header.push_back(why);
  ao::write_preset(preset, header);
  if (!a.json.empty()) write_text(a.json, result_json(a, r).dump(2) + "\n");
  print_result(a, r);
  return kExitSame;
}

}  // namespace

void add_tune_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<TuneArgs>();
  CLI::App* cmd = app.add_subcommand(
      "tune", "Search a technique's parameters against the ray-traced reference; write a preset");
  cmd->add_option("--technique", a->technique, rd::technique_names("|"))->required();
  cmd->add_option("--radius", a->s.radii, "radius in scene units, repeatable")
      ->capture_default_str();
  cmd->add_option("--scenes", a->scenes,
                  "built-in scenes or scene files, comma-separated (default: every built-in, the "
                  "dragon if fetched, and ./suites/scenes/*.toml that load)")
      ->delimiter(',');
  cmd->add_option("--width", a->s.width)->capture_default_str();
  cmd->add_option("--height", a->s.height)->capture_default_str();
  cmd->add_option("--rays", a->s.rays, "reference rays per pixel")->capture_default_str();
  cmd->add_option("--trials", a->s.search.trials, "candidates measured per search")
      ->capture_default_str();
  cmd->add_option("--seed", a->s.search.seed)->capture_default_str();
  cmd->add_option("--budget-taps", a->s.search.budget_taps,
                  "most depth fetches per pixel (18: GTAO's High preset)")
      ->capture_default_str();
  cmd->add_option("--out", a->out, "the preset (default reports/tune/TECHNIQUE.toml)");
  cmd->add_option("--state", a->state,
                  "the measurements, reused by a rerun (default: the preset's name + .state.json)");
  cmd->add_option("--json", a->json, "write the result as JSON");
  cmd->add_option("--max-worse-share", a->s.bar.worse_share,
                  "largest share of held-out (scene, radius) pairs the preset may make worse "
                  "than the defaults (default 0.1)")
      ->option_text("0..1")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--max-worse-ratio", a->s.bar.worst_ratio,
                  "largest error over the defaults' the preset may have on a held-out pair "
                  "(default 1.05)")
      ->option_text("1..100")
      ->check(CLI::Range(1.0, 100.0));
  add_pipeline_option(cmd, a->pipeline);
  guarded(cmd, rc, "tune", [a] { return run_tune(*a); });
}

}  // namespace aosuite::cli

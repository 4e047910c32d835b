#include "ao/tune_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "ao/timed_render.hpp"
#include "common/file_io.hpp"
#include "reference/error_metrics.hpp"
#include "reference/reference_cache.hpp"
#include "renderer/passes/shader_library.hpp"
#include "renderer/pmi/pmi_object.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::ao {
namespace {

namespace rd = aosuite::renderer;
namespace ref = aosuite::reference;
namespace fs = std::filesystem;

// One view of one scene at one radius, with its reference and the pixels that count.
struct Item {
  const rd::Scene* scene;
  const rd::View* view;
  std::size_t scene_index;
  std::size_t radius_index;
  float radius;
  std::string key;  // "scene/view/r/reference key"
  cv::Mat reference, mask;
  int pixels;  // in the mask
};

// The measurements, by parameters (TuneSpace::key) and item, in a JSON file that names the
// settings they were made under.
class Measurements {
 public:
  explicit Measurements(fs::path file) : file_(std::move(file)) {}

  // Reads the file, if there is one, and refuses it unless it was measured under `settings`
  // (technique, size, rays, the GL renderer and the shaders' hash).
  void open(nlohmann::json settings) {
    header_ = std::move(settings);
    if (file_.empty() || !fs::exists(file_)) return;
    const std::vector<unsigned char> bytes = read_file(file_);
    const nlohmann::json j = nlohmann::json::parse(bytes.begin(), bytes.end(), nullptr, false);
    const auto objects = [](const nlohmann::json& e) {
      return e.is_object() && std::ranges::all_of(e, [](const auto& v) { return v.is_object(); });
    };
    if (j.is_discarded() || !j.is_object() || !j.contains("settings") || !j.contains("errors") ||
        !objects(j["errors"]))
      throw FileError(fmt::format("{}: not a tune state file", file_.string()));
    if (j["settings"] != header_) {
      throw FileError(
          fmt::format("{}: measured under other settings ({}, not {}); give another "
                      "--state or delete it",
                      file_.string(), j["settings"].dump(), header_.dump()));
    }
    errors_ = j["errors"];
  }

  std::optional<double> find(const std::string& params, const std::string& item) const {
    const auto p = errors_.find(params);
    if (p == errors_.end()) return std::nullopt;
    const auto e = p->find(item);
    if (e == p->end() || !e->is_number()) return std::nullopt;
    return e->get<double>();
  }

  void add(const std::string& params, const std::string& item, double error) {
    errors_[params][item] = error;
    dirty_ = true;
  }

  void save() {
    if (file_.empty() || !dirty_) return;
    if (file_.has_parent_path()) fs::create_directories(file_.parent_path());
    write_text(file_, nlohmann::json{{"settings", header_}, {"errors", errors_}}.dump(1) + "\n");
    dirty_ = false;
  }

 private:
  fs::path file_;
  nlohmann::json header_, errors_ = nlohmann::json::object();
  bool dirty_ = false;
};

class Evaluator {
 public:
  Evaluator(const TuneSettings& s, const TuneSpace& space, Measurements& m)
      : s_(s), space_(space), m_(m) {
    for (const std::string& name : s.scenes) scenes_.push_back(rd::load_scene(name));
    for (std::size_t i = 0; i < scenes_.size(); ++i) add_items(i);
    if (items_.empty()) {
      throw std::invalid_argument(fmt::format(
          "no view of the scenes can be measured (left out: {})", fmt::join(left_out_, "; ")));
    }
  }

  const std::deque<Item>& items() const { return items_; }
  std::string gl() const { return renderer_.gl_description(); }
  const std::deque<rd::Scene>& scenes() const { return scenes_; }
  const std::vector<std::string>& left_out() const { return left_out_; }
  int renders() const { return renders_; }
  int reused() const { return reused_; }

  double error(const rd::AoParams& params, const Item& item) {
    const std::string key = space_.key(params);
    if (const std::optional<double> e = m_.find(key, item.key)) {
      ++reused_;
      return *e;
    }
    const rd::Images img = renderer_.render(*item.scene, *item.view, settings(params, item.radius));
    const double e = ref::masked_rmse(img.ao, item.reference, item.mask);
    ++renders_;
    m_.add(key, item.key, e);
    return e;
  }

  // The median AO time of a frame at the tune's size, over `runs` runs.
  double ao_ms(const rd::AoParams& params, const Item& item, int runs) {
    return render_timed(renderer_, *item.scene, *item.view, settings(params, item.radius), runs)
        .gl_ms;
  }

  // The mean over the items `take` accepts.
  template <typename Take>
  double mean(const rd::AoParams& params, Take take) {
    double sum = 0;
    int n = 0;
    for (const Item& item : items_) {
      if (take(item)) sum += error(params, item), ++n;
    }
    return n ? sum / n : 0;
  }

  // Each (scene, radius) pair's error among the items `take` accepts, the mean over its views,
  // by (scene index, radius index).
  template <typename Take>
  std::map<std::pair<std::size_t, std::size_t>, double> pair_errors(const rd::AoParams& params,
                                                                    Take take) {
    std::map<std::pair<std::size_t, std::size_t>, std::pair<double, int>> sums;
    for (const Item& item : items_) {
      if (!take(item)) continue;
      auto& [sum, n] = sums[{item.scene_index, item.radius_index}];
      sum += error(params, item), ++n;
    }
    std::map<std::pair<std::size_t, std::size_t>, double> out;
    for (const auto& [pair, s] : sums) out[pair] = s.first / s.second;
    return out;
  }

  // Each pair's error under `params` over the defaults' there (error_ratio), in pair order.
  template <typename Take>
  std::vector<double> ratios(const rd::AoParams& params, const rd::AoParams& defaults, Take take) {
    const auto p = pair_errors(params, take), d = pair_errors(defaults, take);
    std::vector<double> out;
    for (const auto& [pair, e] : p) out.push_back(error_ratio(e, d.at(pair)));
    return out;
  }

 private:
  // The float AO alone, at the item's radius.
  rd::RenderSettings settings(const rd::AoParams& params, float radius) const {
    rd::RenderSettings rs;
    rs.width = s_.width, rs.height = s_.height, rs.technique = s_.technique;
    rs.params = params;
    rs.params.radius = radius;
    rs.outputs = rd::Outputs{false, false, false, true};
    rs.pipeline = s_.pipeline;
    return rs;
  }

  void add_items(std::size_t index) {
    const rd::Scene& scene = scenes_[index];
    // A scene the technique cannot draw is left out with the reason, before its references are
    // made: an object-space technique (PMI) needs an object besides the ground.
    if (rd::object_space(s_.technique)) {
      try {
        rd::pmi_object(scene);
      } catch (const std::invalid_argument& e) {
        left_out_.push_back(fmt::format("{}: {}", scene.name, e.what()));
        return;
      }
    }
    ref::ReferenceCache cache(scene, ref::default_cache_dir());
    for (const rd::View& view : scene.views) {
      const rd::Images g = renderer_.render(scene, view, rd::gbuffer_settings(s_.width, s_.height));
      cv::Mat mask = ref::geometry_mask(g.depth, 8);
      const int pixels = cv::countNonZero(mask);
      if (pixels == 0) {  // nothing drawn, or only within the border
        left_out_.push_back(scene.name + "/" + view.name + ": draws no geometry");
        continue;
      }
      const rd::Camera camera = rd::make_camera(view, s_.width, s_.height);
      for (std::size_t r = 0; r < s_.radii.size(); ++r) {
        const float radius = s_.radii[r];
        const ref::ReferenceSettings rs{s_.rays, radius, ref::Variant::kAo};
        // The reference's key covers the geometry, camera and G-buffer: an edited scene
        // file is a new item, never an old measurement.
        items_.push_back({&scene, &view, index, r, radius,
                          fmt::format("{}/{}/{}/{}", scene.name, view.name, radius,
                                      cache.key(camera, g.depth, g.normal, rs)),
                          cache.get(camera, g.depth, g.normal, rs), mask, pixels});
      }
    }
  }

  const TuneSettings& s_;
  const TuneSpace& space_;
  Measurements& m_;
  rd::Renderer renderer_;
  std::deque<rd::Scene> scenes_;  // items point into it
  std::deque<Item> items_;
  std::vector<std::string> left_out_;
  int renders_ = 0, reused_ = 0;
};

// Each measured scene's fold: its family, or the scene itself where it names none; a fold per
// scene when the scenes make fewer than two families (nothing else could be left out).
std::vector<std::string> fold_groups(const std::deque<rd::Scene>& scenes,
                                     const std::vector<std::size_t>& measured) {
  std::vector<std::string> group(scenes.size());
  for (std::size_t i : measured)
    group[i] = scenes[i].family.empty() ? scenes[i].name : scenes[i].family;
  const bool one_family = std::ranges::all_of(
      measured, [&](std::size_t i) { return group[i] == group[measured.front()]; });
  if (one_family) {
    for (std::size_t i : measured) group[i] = scenes[i].name;
  }
  return group;
}

// Each shrink on the held-out pairs: every fold's parameters moved that share of the way from
// the defaults, measured on the fold's own held-out scenes (never on those it searched on).
std::vector<ShrinkTrial> shrink_trials(Evaluator& ev, const TuneSpace& space, const TuneResult& out,
                                       const std::vector<std::string>& groups,
                                       const std::vector<std::string>& group,
                                       const std::vector<rd::AoParams>& fold_params,
                                       const HeldOutBar& bar, std::size_t radii, int budget) {
  std::vector<ShrinkTrial> trials;
  if (out.folds.empty()) return trials;
  for (int eighths = 0; eighths <= 8; ++eighths) {
    ShrinkTrial t;
    t.shrink = eighths / 8.0;
    std::vector<double> all;
    for (std::size_t f = 0; f < out.folds.size(); ++f) {
      const auto held = [&](const Item& i) { return group[i.scene_index] == groups[f]; };
      const rd::AoParams p = space.between(out.defaults, fold_params[f], t.shrink);
      t.within_budget = t.within_budget && (t.shrink == 0 || depth_taps(space, p) <= budget);
      const std::vector<double> ratios = ev.ratios(p, out.defaults, held);
      ShrinkTrial fold;
      summarise(fold, ratios, bar);
      t.fold_ratio.push_back(fold.mean_ratio);
      all.insert(all.end(), ratios.begin(), ratios.end());
      std::vector<double>& errors = t.fold_error.emplace_back();
      for (std::size_t k = 0; k < radii; ++k)
        errors.push_back(ev.mean(p, [&](const Item& i) { return held(i) && i.radius_index == k; }));
    }
    summarise(t, all, bar);
    trials.push_back(t);
  }
  return trials;
}

void check(const TuneSettings& s) {
  if (s.scenes.empty()) throw std::invalid_argument("tune needs at least one scene");
  if (s.radii.empty()) throw std::invalid_argument("tune needs at least one radius");
  for (float r : s.radii) {
    if (!(r > 0) || !std::isfinite(r))
      throw std::invalid_argument(fmt::format("radius must be > 0 (got {})", r));
  }
  if (s.width < 16 || s.height < 16) throw std::invalid_argument("tune renders at least 16x16");
  if (s.search.trials < 1) throw std::invalid_argument("trials must be >= 1");
  ref::validate({s.rays, s.radii.front(), ref::Variant::kAo});
}

}  // namespace

TuneResult run_tune(const TuneSettings& s, const std::function<void(const TuneProgress&)>& on) {
  check(s);
  const TuneSpace space(s.technique);
  Measurements m(s.state);
  Evaluator ev(s, space, m);
  m.open({{"technique", std::string(rd::technique_name(s.technique))},
          {"width", s.width},
          {"height", s.height},
          {"rays", s.rays},
          {"gl", ev.gl()},
          {"shaders", rd::shaders_hash()}});
  TuneResult out;
  out.defaults = rd::default_params(s.technique);
  out.default_taps = depth_taps(space, out.defaults);
  out.left_out = ev.left_out();

  // One search on the items `take` accepts, reporting as `stage`; saves after each trial.
  auto searched = [&](const std::string& stage, auto take) {
    const SearchResult r = search(
        space, out.defaults, s.search,
        [&](const rd::AoParams& p) { return objective(ev.ratios(p, out.defaults, take)); },
        [&](int trial, double best) {
          m.save();
          if (on) on({stage, trial, s.search.trials, best, false});
        });
    if (on) on({stage, r.trials, s.search.trials, r.error, true});
    return r;
  };
  // The scenes with something to measure (a scene whose every view is empty has none).
  std::vector<std::size_t> measured;
  for (std::size_t i = 0; i < ev.scenes().size(); ++i) {
    if (std::ranges::any_of(ev.items(), [i](const Item& it) { return it.scene_index == i; }))
      measured.push_back(i);
  }
  for (std::size_t i : measured) out.scenes.push_back(s.scenes[i]);
  const std::vector<std::string> group = fold_groups(ev.scenes(), measured);
  std::vector<std::string> groups;  // in the order of their first scene
  for (std::size_t i : measured) {
    if (std::ranges::find(groups, group[i]) == groups.end()) groups.push_back(group[i]);
  }
  const std::size_t n = groups.size();
  std::vector<rd::AoParams> fold_params;  // each fold's search result
  for (std::size_t fold_index = 0; n >= 2 && fold_index < n; ++fold_index) {
    const std::string& g = groups[fold_index];
    const auto in_fold = [&group, &g](const Item& i) { return group[i.scene_index] == g; };
    const SearchResult r = searched(fmt::format("fold {}/{} (held out: {})", fold_index + 1, n, g),
                                    [&](const Item& i) { return !in_fold(i); });
    Fold fold{g, {}, {}, space.key(r.best), {}};
    fold_params.push_back(r.best);
    for (std::size_t k = 0; k < s.radii.size(); ++k) {
      auto held = [&](const Item& i) { return in_fold(i) && i.radius_index == k; };
      fold.default_error.push_back(ev.mean(out.defaults, held));
      fold.tuned_error.push_back(ev.mean(r.best, held));
    }
    for (std::size_t i : measured) {
      if (group[i] != g) continue;
      auto scene = [i](const Item& it) { return it.scene_index == i; };
      fold.scenes.push_back(
          {ev.scenes()[i].name, ev.mean(out.defaults, scene), ev.mean(r.best, scene)});
    }
    out.folds.push_back(std::move(fold));
  }
  out.shrink_trials = shrink_trials(ev, space, out, groups, group, fold_params, s.bar,
                                    s.radii.size(), s.search.budget_taps);
  out.shrink = choose_shrink(out.shrink_trials);
  const auto every = [](const Item&) { return true; };
  // A preset the folds keep at the defaults needs no search on every scene.
  out.searched = out.shrink > 0 ? searched("all scenes", every).best : out.defaults;
  out.tuned = space.between(out.defaults, out.searched, out.shrink);
  // Whole-number parameters rounded between the defaults and the search can cost more than
  // either: a share whose preset is over the budget is not taken.
  while (out.shrink > 0 && depth_taps(space, out.tuned) > s.search.budget_taps) {
    std::ranges::find(out.shrink_trials, out.shrink, &ShrinkTrial::shrink)->within_budget = false;
    out.shrink = choose_shrink(out.shrink_trials);
    out.tuned = space.between(out.defaults, out.searched, out.shrink);
  }
  out.tuned_error = ev.mean(out.tuned, every);
  out.tuned_taps = depth_taps(space, out.tuned);
  out.default_error = ev.mean(out.defaults, every);
  m.save();
  // Timed on the view with the most geometry pixels: the one where the AO does most work.
  const Item& busiest = *std::ranges::max_element(ev.items(), {}, &Item::pixels);
  out.default_ms = ev.ao_ms(out.defaults, busiest, 9);
  out.tuned_ms = ev.ao_ms(out.tuned, busiest, 9);
  out.timed_view = busiest.scene->name + "/" + busiest.view->name;
  out.renders = ev.renders(), out.reused = ev.reused();
  return out;
}

}  // namespace aosuite::ao

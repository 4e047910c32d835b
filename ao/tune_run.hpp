// `aosuite tune`: one technique's parameters searched (ao/tune_search.hpp) against the
// ray-traced reference at the same radius (the AO term's RMSE over geometry pixels, as
// `aosuite error` prints it under "all"), over every view of a set of scenes at one or more
// radii. A candidate is judged by each (scene, radius) pair's error as a ratio to the defaults'
// there, the worst and the mean of those ratios together (issue 45): the mean error alone is
// decided by the scenes with the most error, and a candidate that wins there at another
// scene's cost fits the training family rather than the technique. It is validated by leaving one
// family of scenes out at a time (renderer::Scene::family; one scene at a time when all are of one
// family): each fold searches on the other families and is measured on the one left out, which the
// search never saw. The preset is then searched on every scene. Measurements are kept in a state
// file, so a rerun with the same settings (interrupted or not) measures nothing twice and gives the
// same result.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ao/tune_choice.hpp"
#include "ao/tune_search.hpp"

namespace aosuite::ao {

struct TuneSettings {
  renderer::Technique technique = renderer::Technique::kGtao;
  std::vector<float> radii{1};
  std::vector<std::string> scenes;  // built-in names or scene files; every view of each
  int width = 320, height = 180;
  int rays = 256;  // the reference's rays per pixel
  SearchOptions search;
  std::filesystem::path state;  // the measurements; empty: kept in memory only
  // Unset: the device's. The timed frames' pipeline; the AO, so the search, is the same in both.
  std::optional<renderer::Pipeline> pipeline;
  HeldOutBar bar;
};

// A held-out scene's error under the defaults and under its fold's parameters, each the mean
// over its views and the radii.
struct HeldOutScene {
  std::string scene;
  double default_error = 0, tuned_error = 0;
};

// One family (or scene) left out: its error under the defaults and under the parameters
// searched on the others, per radius (TuneSettings::radii order), each the mean over its
// scenes' views; and each of its scenes apart, so a mean cannot hide one that got worse.
struct Fold {
  std::string held_out;  // the family, or the scene when the folds are per scene
  std::vector<double> default_error, tuned_error;
  std::string params;  // TuneSpace::key of what this fold's search found
  std::vector<HeldOutScene> scenes;
};

struct TuneResult {
  // The technique's defaults; the search on every scene; the preset: that search moved a share
  // `shrink` of the way from the defaults (the search itself without folds to choose by). When
  // the folds keep the defaults (shrink 0) there is no search on every scene: `searched` is the
  // defaults.
  renderer::AoParams defaults, searched, tuned;
  double shrink = 1;
  std::vector<ShrinkTrial> shrink_trials;     // empty without folds
  double default_error = 0, tuned_error = 0;  // mean over every scene, view and radius (preset)
  int default_taps = 0, tuned_taps = 0;
  // The median AO time of one frame at the tune's size, on the view with the most geometry:
  // what the depth-tap budget stands for, measured, not used by the search (not repeatable).
  double default_ms = 0, tuned_ms = 0;
  std::string timed_view;       // "scene/view"
  std::vector<Fold> folds;      // one per scene when there are two or more
  int renders = 0, reused = 0;  // measurements made, and taken from the state file
  // Left out, with why: "scene/view: draws no geometry", or "scene: REASON" for a scene the
  // technique cannot draw (PMI on ground alone).
  std::vector<std::string> left_out;
  std::vector<std::string> scenes;  // the settings' scenes that were measured, in their order
};

struct TuneProgress {
  std::string stage;  // "fold 2/6 (held out: village)" or "all scenes"
  int trial = 0, trials = 0;
  double best = 0;    // the best candidate's objective: its error over the defaults' (tune_run.cpp)
  bool done = false;  // the stage's last report (a search may end before its trials)
};

// Throws std::invalid_argument for a bad setting (no scene, a technique with nothing to search)
// and FileError for a state file made with other settings or unreadable.
TuneResult run_tune(const TuneSettings& settings,
                    const std::function<void(const TuneProgress&)>& on_progress = {});

}  // namespace aosuite::ao

// How `aosuite tune` judges a candidate and chooses how far its preset moves from the defaults
// (issue 45), apart from the renders: the error ratio to the defaults, the search's objective,
// and the share of the way from the defaults chosen on held-out (scene, radius) pairs.
#pragma once

#include <vector>

namespace aosuite::ao {

// What a preset may cost on scenes it was not tuned on: at most a share `worse_share` of the
// held-out (scene, radius) pairs worse than the defaults, none by a ratio over `worst_ratio`.
struct HeldOutBar {
  double worse_share = 0.1;
  double worst_ratio = 1.05;
};

// One share `shrink` of the way from the defaults to each fold's search result, measured on the
// (scene, radius) pairs the fold left out, each pair's error (the mean over its views) as a
// ratio to the defaults' there (error_ratio).
struct ShrinkTrial {
  double shrink = 0;
  int pairs = 0, worse = 0;  // held-out pairs, and those worse than the defaults
  double worst_ratio = 1;    // the worst pair's error over the defaults' there
  double mean_ratio = 1;     // the pairs' geometric mean
  double log_se = 0;         // the standard error of the pairs' mean log ratio
  bool within_bar = true;
  // Every fold's parameters at this share within the search's depth-tap budget (share 0, the
  // defaults themselves, always is).
  bool within_budget = true;
  std::vector<double> fold_ratio;  // each fold's geometric mean ratio, in TuneResult::folds order
  // Each fold's AO RMSE per radius (TuneSettings::radii order), the mean over its held-out
  // views: what techniques are ranked by on a family none of them was tuned on.
  std::vector<std::vector<double>> fold_error;
};

// An error over the defaults' on the same pair, each with 1e-3 added (a tenth of a per cent of
// AO's range, below the reference's own noise at any ray count a tune uses): keeps the ratio
// finite where the defaults are exact (an open plane), where it is then large but bounded.
double error_ratio(double error, double default_error);

// The search's objective: the worst and the mean of the pairs' ratios, averaged (1 for the
// defaults themselves). The worst alone would ignore every pair but one; the mean alone lets
// one pair get much worse.
double objective(const std::vector<double>& ratios);

// Sets t's pairs, worse, worst_ratio, mean_ratio, log_se and within_bar from the held-out pairs'
// ratios. A ratio that is not a number counts as worse and over the bar.
void summarise(ShrinkTrial& t, const std::vector<double>& ratios, const HeldOutBar& bar);

// The share chosen (trials in increasing share, share 0 first): of the trials within the bar
// and the budget, the best has the lowest mean ratio; the chosen one is the smallest whose mean
// log ratio is within one standard error of the best's (Breiman's one-standard-error rule: a
// gain the held-out pairs cannot tell from noise is no evidence), so 0, the defaults, when the
// best gain is within its own standard error. 1 (the search's own result) without trials.
double choose_shrink(const std::vector<ShrinkTrial>& trials);

}  // namespace aosuite::ao

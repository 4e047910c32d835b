// The search behind `aosuite tune`: the technique's defaults (their sample, slice or step
// count lowered to fit the budget if need be), then random points of the search space (the
// same points for the same seed, whatever they score, so the folds of a cross-validation share
// their measurements), then a pattern search from the best point so far (one coordinate at a
// time, halving the step when no move improves), every candidate within the depth-tap budget.
// Minimises any objective: tune_run.hpp gives it the mean AO error against the ray-traced
// reference.
#pragma once

#include <cstdint>
#include <functional>

#include "ao/tune_space.hpp"

namespace aosuite::ao {

struct SearchOptions {
  int trials = 48;            // candidates measured, the start included
  std::uint64_t seed = 1;     // the random points
  int budget_taps = 18;       // TechniqueInfo::depth_taps at most (GTAO's High preset)
  double random_share = 0.4;  // of the trials spent on random points
};

struct SearchResult {
  renderer::AoParams best;
  double error = 0;
  int trials = 0;  // candidates measured
};

// `start`: the parameters the search begins from (the defaults, the radius set) and whose
// other fields every candidate keeps. `on_trial(trial, best_error)` after each candidate.
// Throws std::invalid_argument when no candidate fits the budget.
SearchResult search(const TuneSpace& space, const renderer::AoParams& start,
                    const SearchOptions& options,
                    const std::function<double(const renderer::AoParams&)>& objective,
                    const std::function<void(int, double)>& on_trial = {});

// The depth taps per pixel of `p` for the space's technique.
int depth_taps(const TuneSpace& space, const renderer::AoParams& p);

}  // namespace aosuite::ao

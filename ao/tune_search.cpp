#include "ao/tune_search.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <variant>

namespace aosuite::ao {
namespace {

namespace rd = aosuite::renderer;

// The next double in [0, 1) from the engine's 53 high bits: the same on every platform, which
// std::uniform_real_distribution does not promise.
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

class Search {
 public:
  Search(const TuneSpace& space, const rd::AoParams& start, const SearchOptions& o,
         const std::function<double(const rd::AoParams&)>& objective,
         const std::function<void(int, double)>& on_trial)
      : space_(space), start_(start), o_(o), objective_(objective), on_trial_(on_trial) {}

  SearchResult run() {
    try_point(space_.point(within_budget(start_)));
    std::mt19937_64 rng(o_.seed);
    const int random_trials = static_cast<int>(std::lround(o_.trials * o_.random_share));
    // A bounded number of draws: a budget few points fit must not spin forever.
    for (int draw = 0; draw < 100 * o_.trials && trials_ < random_trials; ++draw) {
      std::vector<double> p(space_.dimensions().size());
      for (double& x : p) x = unit(rng);
      try_point(p);
    }
    if (best_point_.empty()) {
      throw std::invalid_argument(fmt::format("no {} parameters fit a budget of {} depth taps",
                                              rd::technique_name(space_.technique()),
                                              o_.budget_taps));
    }
    pattern_search();
    return {space_.params(best_point_, start_), best_error_, trials_};
  }

 private:
  // `p` with its largest integer parameter (samples, slices or steps) lowered one at a time
  // until it fits the budget: the defaults of a technique that costs more (UE4's 8 directions
  // are 48 taps) start the search at their nearest affordable version.
  rd::AoParams within_budget(rd::AoParams p) const {
    while (depth_taps(space_, p) > o_.budget_taps) {
      const rd::ParamSpec* largest = nullptr;
      int most = 0;
      for (const Dimension& d : space_.dimensions()) {
        const int v = d.integer ? std::get<int>(rd::param_value(*d.spec, p)) : 0;
        if (v > most && v > d.spec->search.lo) largest = d.spec, most = v;
      }
      if (!largest) break;  // nothing left to lower: the random points may still fit
      rd::set_param(p, largest->key, std::to_string(most - 1));
    }
    return p;
  }

  // Measures a point unless it is over the budget, outside the trials or already measured
  // (it rounds to parameters seen before). Returns whether it improved on the best.
  bool try_point(const std::vector<double>& p) {
    if (trials_ >= o_.trials) return false;
    const rd::AoParams params = space_.params(p, start_);
    if (depth_taps(space_, params) > o_.budget_taps) return false;
    if (!seen_.insert(space_.key(params)).second) return false;
    const double e = objective_(params);
    ++trials_;
    const bool better = e < best_error_;
    if (better) best_error_ = e, best_point_ = space_.point(params);
    if (on_trial_) on_trial_(trials_, best_error_);
    return better;
  }

  // The best point moved by `delta` along dimension `d`. A whole-number parameter that the move
  // would round back to its value moves one whole step instead: the steps are fractions of a
  // range, and rounding would otherwise swallow them (a 0/1 switch would never flip).
  std::vector<double> moved(std::size_t d, double delta) const {
    std::vector<double> p = best_point_;
    p[d] = std::clamp(p[d] + delta, 0.0, 1.0);
    const Dimension& dim = space_.dimensions()[d];
    if (!dim.integer) return p;
    const rd::AoParams from = space_.params(best_point_, start_);
    const int now = std::get<int>(rd::param_value(*dim.spec, from));
    const int next = now + (delta > 0 ? 1 : -1);
    if (std::get<int>(rd::param_value(*dim.spec, space_.params(p, start_))) != now ||
        next < dim.spec->search.lo || next > dim.spec->search.hi)
      return p;
    rd::AoParams to = from;
    rd::set_param(to, dim.spec->key, std::to_string(next));
    return space_.point(to);
  }

  // One coordinate at a time, both directions, from the best point; the step halves when a
  // full round finds nothing better, down to 1/64 of a range.
  void pattern_search() {
    for (double step = 0.25; step >= 1.0 / 64 && trials_ < o_.trials;) {
      bool improved = false;
      for (std::size_t d = 0; d < best_point_.size() && trials_ < o_.trials; ++d) {
        for (double sign : {1.0, -1.0}) {
          if (try_point(moved(d, sign * step))) {
            improved = true;
            break;
          }
        }
      }
      if (!improved) step /= 2;
    }
  }

  const TuneSpace& space_;
  const rd::AoParams& start_;
  const SearchOptions& o_;
  const std::function<double(const rd::AoParams&)>& objective_;
  const std::function<void(int, double)>& on_trial_;
  std::set<std::string> seen_;
  std::vector<double> best_point_;
  double best_error_ = std::numeric_limits<double>::infinity();
  int trials_ = 0;
};

}  // namespace

int depth_taps(const TuneSpace& space, const rd::AoParams& p) {
  return rd::technique_info(space.technique()).depth_taps(p);
}

SearchResult search(const TuneSpace& space, const rd::AoParams& start, const SearchOptions& o,
                    const std::function<double(const rd::AoParams&)>& objective,
                    const std::function<void(int, double)>& on_trial) {
  return Search(space, start, o, objective, on_trial).run();
}

}  // namespace aosuite::ao

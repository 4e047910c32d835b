// `aosuite tolerances suggest`: from several runs of a suite (the reports `check` wrote, on
// other machines or retries), a tolerance per case that passes every one of them, widened by a
// margin that a run held back from the others needed, so that the next run passes too (as
// Skia Gold's inexact-matching parameter search proposes one). A proposal to review: the suite
// and its goldens are never touched.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "harness/suite.hpp"

namespace aosuite::harness {

struct SuggestOptions {
  // Relative headroom: each max limit is the largest value plus margin % of it, each min limit
  // the smallest less as much, before rounding outward. None: each case's margin is chosen
  // from its runs so that a run held back from the others passes (`Suggestion::margin_why`).
  std::optional<double> margin_percent;
};

struct Suggestion {
  std::string id;
  std::vector<std::string> runs;  // the report folders it is based on
  std::string reason;             // why nothing is suggested; empty when something is
  Tolerance current;              // the suite's tolerance now
  // `current` with its limits set from what the runs measured. `resemble` is off when no image
  // had Resemble's numbers (float images): then its keys are not suggested.
  Tolerance proposed;
  // Limits left as the suite has them, and why ("flip max_mean: no run measured it ...").
  std::vector<std::string> kept;
  // The margin the limits got, in % of each measured value (rounded up to 4 significant digits
  // for show), and why: "--margin", or "the farthest a held-back run fell from the others' limit
  // (max_mismatch_percent in reports/c)"; then the limits that got none or start elsewhere, and
  // why.
  double margin_percent = 0;
  std::string margin_why;
  std::vector<std::string> margin_notes;
};

// One suggestion per case of the suite, in its order. A suggestion needs two runs or more, each
// of which measured every image of the case against the golden the suite has now, under the
// same mode, mask, ignored boxes and foreground, with every gated stat measured; else `reason`
// says which run lacks what. Throws std::runtime_error, naming the results.json, for a report
// that cannot be read, is of another suite or judged another goldens folder, or is given twice.
std::vector<Suggestion> suggest(const Suite& suite,
                                const std::vector<std::filesystem::path>& reports,
                                const SuggestOptions& options);

// Folder mode: the suite `check --actual A --expected E` made for the folders the first of
// `reports` (folder-mode runs) compared, each image under the tolerance a run judged it by.
// Throws std::runtime_error naming the results.json when it is a suite's run or unreadable.
Suite folder_suite_of(const std::vector<std::filesystem::path>& reports);

// Folder mode has one tolerance for every image: the loosest of the suggestions made (each
// max limit the largest, each min limit the smallest); nothing when none was made.
std::optional<Tolerance> loosest(const std::vector<Suggestion>& suggestions);

// The folder-mode flags that set `t`: "--max-mismatch 0.5 --max-channel-delta 3
// --gate flip.max_mean=0.0123".
std::string folder_flags(const Tolerance& t);

// Calls f(region, gates, limit) for each limit of `t`'s gates (region "") and of its regions'.
template <typename T, typename F>
void for_each_limit(T& t, F f) {
  for (auto& g : t.gates)
    for (auto& l : g.limits) f(std::string_view(), g, l);
  for (auto& r : t.regions)
    for (auto& g : r.gates)
      for (auto& l : g.limits) f(std::string_view(r.name), g, l);
}

// `v` rounded to 4 significant digits away from the measured side (up for a max limit, down for
// a min one), so the limit never cuts off what was measured and stays readable.
double round_outward(double v, bool up);

}  // namespace aosuite::harness

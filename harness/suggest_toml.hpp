// The file `aosuite tolerances suggest` writes into the report folder: the suggestions as TOML
// in the suite's own syntax, one complete [case.tolerance] table per case, for a person to
// review and paste into the suite.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harness/tolerance_suggest.hpp"

namespace aosuite::harness {

// A header naming the suite, the runs and the rule; per suggested case a comment naming it and
// its margin, then its [case.tolerance]: the suggested limits (mode beside Resemble's, regions
// with their colours), each followed by what the suite says now, and the keys not suggested
// as the case has them; then the cases not suggested, and why.
std::string suggestions_toml(const Suite& suite, const std::vector<Suggestion>& suggestions,
                             const std::vector<std::filesystem::path>& reports,
                             const SuggestOptions& options);

// "+12.5 % on each limit, the farthest a held-back run fell from the others' limit
// (max_channel_delta in reports/c)".
std::string margin_text(const Suggestion& s);

// "flip = { max_mean = 0.01234, max_q3 = 0.2 }": a metric's gates as the suite writes them.
std::string gates_toml(const metric::Gates& g);

}  // namespace aosuite::harness

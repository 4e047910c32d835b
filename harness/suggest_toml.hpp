// The file `aosuite tolerances suggest` writes beside the goldens: the suggestions as TOML in
// the suite's own keys, for a person to review and copy into the suite.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "harness/tolerance_suggest.hpp"

namespace aosuite::harness {

// A header naming the suite, the runs and the rule; one table per suggested case, keyed by its
// id, holding the limits the suite's tolerance has (mode beside Resemble's, regions with their
// colours), each followed by what the suite says now; then the cases not suggested, and why.
std::string suggestions_toml(const Suite& suite, const std::vector<Suggestion>& suggestions,
                             const std::vector<std::filesystem::path>& reports,
                             const SuggestOptions& options);

// "flip = { max_mean = 0.01234, max_q3 = 0.2 }": a metric's gates as the suite writes them.
std::string gates_toml(const metric::Gates& g);

}  // namespace aosuite::harness

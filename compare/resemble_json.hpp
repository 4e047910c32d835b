// Resemble.js's shapes in JSON: the result line resemble-oracle prints, and the option
// objects its batch files carry, so one batch file drives both tools.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "compare/resemble.hpp"

namespace aosuite::resemble {

// One line with Resemble's keys in Resemble's order; numbers printed as JavaScript prints
// them. `extra` (may be null) is appended as further keys, e.g. id, a, b in batch mode.
std::string result_json(const Result& r, const nlohmann::ordered_json& extra = nullptr);

// Applies the keys of a resemble-oracle batch object (mode, largeImageThreshold, errorType,
// errorColor, transparency, boundingBoxes, ignoredBoxes, ignoreAreasColoredWith,
// returnEarlyThreshold, tolerance) on top of `options`. Throws std::invalid_argument on a
// wrong type or an unsupported key value.
void apply_json_options(const nlohmann::json& j, Options& options);

}  // namespace aosuite::resemble

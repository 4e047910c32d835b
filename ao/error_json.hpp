// The AO error metrics (reference/error_metrics.hpp) as JSON, as `aosuite error --json` prints
// them and sweep.json stores them, and back (`sweep --merge` reads the shards' rows).
#pragma once

#include <nlohmann/json.hpp>

#include "reference/error_metrics.hpp"

namespace aosuite::ao {

nlohmann::ordered_json to_json(const reference::ErrorStats& s);
nlohmann::ordered_json to_json(const reference::ErrorReport& r);
// Their inverses; nlohmann::json's errors for a missing or mistyped key.
reference::ErrorStats error_stats_from_json(const nlohmann::json& j);
reference::ErrorReport error_report_from_json(const nlohmann::json& j);

}  // namespace aosuite::ao

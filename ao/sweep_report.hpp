// Every file a sweep writes, as text: sweep.csv, sweep.json (the head, the rows and the fit on
// one view), sweep.md and per resolution a time-vs-RMSE SVG against the radius-r reference
// (and one against the unbounded reference).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ao/sweep_result.hpp"

namespace aosuite::ao {

struct SweepFile {
  std::string name;  // in the output folder
  std::string text;
};

struct SweepReport {
  std::vector<SweepFile> files;  // in the order to write them
  nlohmann::ordered_json fit;    // fit_on_one_view (ao/sweep_fit.hpp), as sweep.json holds it
};

// `shard` ("i/n", or empty for a whole sweep) is recorded in sweep.json.
SweepReport sweep_report(const SweepResult& sweep, const std::string& shard);

}  // namespace aosuite::ao

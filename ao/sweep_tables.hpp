// A sweep's rows as sweep.csv (every metric) and as sweep.md's Markdown tables (the rows and
// the fit on one view), for docs/results.md.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ao/sweep_rows.hpp"

namespace aosuite::ao {

// `unbounded`: the rows carry the error against the unbounded reference (else empty columns).
std::string sweep_csv(const std::vector<Row>& rows, bool unbounded);
// `fit` as fit_on_one_view (ao/sweep_fit.hpp) gives it.
std::string sweep_markdown(const std::vector<Row>& rows, const nlohmann::ordered_json& fit,
                           bool unbounded);

}  // namespace aosuite::ao

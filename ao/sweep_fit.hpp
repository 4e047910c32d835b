// Does a sweep's best configuration carry over to another view? For each scene, technique and
// resolution: the configuration with the lowest RMSE on the first view, and its RMSE on the
// second (beside the second view's own best).
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "ao/sweep_rows.hpp"

namespace aosuite::ao {

// One object per group whose scene has a second view (sweep.json's "fit_on_one_view").
nlohmann::ordered_json fit_on_one_view(const std::vector<Row>& rows);

}  // namespace aosuite::ao

// Runs a sweep grid (ao/sweep_grid.hpp), or one shard of it: per configuration the median AO
// time (all passes but the G-buffer's and the blend's) and the error against the ray-traced
// reference at the technique's radius (and against the unbounded reference).
#pragma once

#include <functional>

#include "ao/sweep_grid.hpp"
#include "ao/sweep_result.hpp"
#include "harness/runner.hpp"

namespace aosuite::ao {

// `shard` takes every shard_count-th configuration from the shard_index-th; the rows keep their
// place in the whole grid (Row::index), so shards merge (ao/sweep_merge.hpp). `on_row` sees
// each row as it is measured.
SweepResult run_sweep(const SweepGrid& g, const harness::Selection& shard,
                      const std::function<void(const Row&)>& on_row);

}  // namespace aosuite::ao

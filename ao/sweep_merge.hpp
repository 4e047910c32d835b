// `aosuite sweep --merge`: the shards' rows (each shard folder's sweep.json) in the grid's
// order, as one run of the whole grid measures them.
#pragma once

#include <string>
#include <vector>

#include "ao/sweep_result.hpp"

namespace aosuite::ao {

// Throws FileError for an unreadable shard, shards of different grids, settings or GL devices
// and a configuration in two shards; std::invalid_argument for configurations missing.
SweepResult merge_sweeps(const std::vector<std::string>& shard_dirs);

}  // namespace aosuite::ao

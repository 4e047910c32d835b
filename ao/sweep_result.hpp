// One sweep's result, whole or one shard's: what every shard of the sweep shares (which a
// merge checks) and the rows it measured.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ao/sweep_rows.hpp"

namespace aosuite::ao {

struct SweepMeta {
  std::string grid, gl, gl_device;
  std::string pipeline;  // fragment|compute: the one the times are of
  int rays = 0, runs = 0;
  bool unbounded = false;
  std::size_t configurations = 0;  // in the whole grid, every shard's rows together
};

struct SweepResult {
  SweepMeta meta;
  std::vector<Row> rows;  // in the grid's order
};

// sweep.json's head; shards of one sweep have equal ones.
nlohmann::ordered_json meta_json(const SweepMeta& m);

}  // namespace aosuite::ao

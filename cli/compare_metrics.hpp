// `aosuite compare --metric/--gate/--heatmap`: the registered metrics (compare/metric.hpp)
// beside Resemble's comparison, on PNG (8- or 16-bit) and EXR images.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "compare/metric.hpp"

namespace aosuite::cli {

struct MetricPlan {
  bool resemble = true;                // Resemble.js's comparison, as without --metric
  std::vector<metric::Gates> metrics;  // each metric to measure, with its gates (maybe none)
  std::string heatmap;                 // where to write FLIP's error map (magma PNG)
  // --flip-pooling tool: FLIP pooled as NVlabs' tool does (metric::Request::tool_pooling) and
  // printed as it prints, 6 decimals.
  bool flip_tool_pooling = false;
};

// From --metric NAME (repeatable; "resemble" or a registered metric), --gate METRIC.KEY=VALUE
// (repeatable; a gate's metric is measured even if not named) and --heatmap FILE (implies
// flip). Resemble alone when none of them is given. Throws std::invalid_argument, one line.
MetricPlan plan_metrics(const std::vector<std::string>& names,
                        const std::vector<std::string>& gates, const std::string& heatmap);

struct MetricRun {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();  // {"flip": {...}, ...}
  std::vector<metric::Outcome> outcomes;  // every gate's, for verdict::decide
  std::vector<std::string> lines;         // one per metric, for people
};

// Measures every planned metric of `b` against `a` (nothing is written; see write_heatmap).
// Throws FileError or std::invalid_argument naming the file and the problem.
MetricRun run_metrics(const MetricPlan& plan, const std::string& a, const std::string& b,
                      std::uint64_t max_bytes, RgbaImage* heatmap);

}  // namespace aosuite::cli

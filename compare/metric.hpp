// The metric seam: one image metric is one Metric (its own file, compare/metric_*.cpp) and one
// line in compare/metric_registry.cpp. `aosuite compare --metric`, the harness's gates,
// results.json, the report and the sweep all iterate the registry; none names a metric.
// Resemble.js's comparison is not one of them: it is the comparator itself, with its own
// options and result object (compare/resemble.hpp), and runs beside them.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "image/picture.hpp"

namespace aosuite::metric {

struct Value {
  std::string key;
  double value = 0;
};

// One metric's result on one pair. Values are finite, but for PSNR's +inf on identical images.
struct Measurement {
  std::string metric;
  std::vector<Value> values;  // the metric's stats, in its order: what gates read
  std::vector<Value> facts;   // how it was measured (data range, exposures): shown, not gated
  // Pixels where either float image holds NaN or Inf. SSIM, RMSE and PSNR read those samples as
  // 0; FLIP as its tool does (NaN as 0, Inf as the largest float).
  std::uint64_t nonfinite = 0;
  RgbaImage map;  // the error map, when asked for and the metric has one
  // > 0: print values with this many decimals, as the metric's reference tool does when asked
  // for its arithmetic (Request::tool_pooling; FLIP's 6); 0: six significant digits.
  int tool_decimals = 0;
  double value(std::string_view key) const;  // throws std::out_of_range for an unknown key
  nlohmann::ordered_json json() const;       // values, then facts, then nonfinite if any
};

struct Request {
  bool want_map = false;
  // width * height flags (row-major): when given, means, percentiles and errors cover only the
  // pixels whose flag is non-zero (geometry, not sky); the map still shows every pixel.
  const std::vector<std::uint8_t>* counted = nullptr;
  // A reference tool's own arithmetic where a metric has one (FLIP, `--flip-pooling tool`:
  // flip::Options::tool_arithmetic, its powf and its float pooling), to print its numbers; fast
  // powers and exact sums otherwise. Metrics without one ignore it.
  bool tool_pooling = false;
};

struct Metric {
  std::string_view name;
  std::string_view summary;  // one line for --help
  std::span<const std::string_view> stats;
  std::string_view primary;  // the stat that a bare `max` or `min` gate limits
  // The kernel: both images have one size and kind (checked before it is called), float
  // images finite (nonfinite samples replaced by 0) unless raw_floats.
  Measurement (*measure)(const Picture& reference, const Picture& test, const Request& request);
  bool raw_floats = false;
  // Its error map is the heat map that `--heatmap` writes and the report shows (one metric).
  bool heatmap = false;
};

std::span<const Metric* const> all();
// Throws std::invalid_argument naming the registered metrics.
const Metric& find(std::string_view name);
std::string names();             // "flip, ssim, rmse, psnr"
const Metric& heatmap_metric();  // the registered metric whose map is the heat map

// `metric` of test against reference. Throws std::invalid_argument, naming both files, for
// images of different sizes or kinds (8-bit against float, one channel against three).
Measurement measure(const Metric& metric, const Picture& reference, const Picture& test,
                    const Request& request = {});

// PSNR in dB of a mean squared error on data of range `data_range`, as scikit-image's
// peak_signal_noise_ratio: 10 log10(range^2 / MSE), exact for every MSE > 0, and +inf for
// identical images (MSE 0; `null` in JSON, `inf` in text and CSV). The project's one PSNR (the
// metric, the AO error statistics): it has no cap, which would merge distinct values of
// near-identical large images (an 8-bit 4K pair one level apart in one pixel is at 129 dB).
double psnr_db(double mse, double data_range = 1.0);

// A limit on one stat: the value must be <= limit (is_max) or >= limit.
struct Limit {
  std::string stat;
  bool is_max = true;
  double limit = 0;
};

// A metric's gates, as a suite's `flip = { max_mean = 0.02, max_q3 = 0.3 }` or the command
// line's `--gate flip.max_mean=0.02` says them: `max`/`min` limit the primary stat,
// `max_<stat>`/`min_<stat>` any stat, and `allow_nonfinite = true` lets NaN or Inf pixels pass.
struct Gates {
  const Metric* metric = nullptr;
  std::vector<Limit> limits;
  bool allow_nonfinite = false;
};
// Adds one `key = value` to `gates`; throws std::invalid_argument naming the accepted keys.
void add_gate(Gates& gates, std::string_view key, double value);
// The metric's entry in the list, added (with no limit) if it has none.
Gates& gates_for(std::vector<Gates>& list, const Metric& m);
// Adds a command line's `METRIC.KEY=VALUE` (VALUE a number, or true/false) to the list, to the
// metric's entry if it has one. Throws std::invalid_argument, one line, for a bad spec.
void add_gate_spec(std::vector<Gates>& list, std::string_view spec);
std::string gate_keys(const Metric& m);  // "max, min, max_mean, min_mean, ..., allow_nonfinite"

struct Outcome {
  std::string metric, stat;  // stat "nonfinite" for the NaN/Inf check
  std::string region;        // the pixels judged, when not the whole image (a region's name)
  double value = 0, limit = 0;
  bool is_max = true;
  double margin = 0;  // how far inside the limit (negative: beyond it), in the stat's units
  bool pass = false;
  std::string text() const;  // "flip mean 0.031 > 0.02", "edges: flip mean 0.031 > 0.02"
};
std::vector<Outcome> judge(const Gates& gates, const Measurement& m);

// As results.json keeps them (infinities as null), and back. Throw nlohmann::json's errors, or
// std::invalid_argument for an unknown metric or gate.
nlohmann::json to_json(const Outcome& o);
Outcome outcome_from_json(const nlohmann::json& j);
Measurement measurement_from_json(const Metric& m, const nlohmann::json& j);
nlohmann::json to_json(const Gates& g);  // {"max_mean": 0.02, ...}
Gates gates_from_json(const Metric& m, const nlohmann::json& j);

}  // namespace aosuite::metric

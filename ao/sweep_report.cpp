#include "ao/sweep_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "ao/sweep_fit.hpp"
#include "ao/sweep_plot.hpp"
#include "ao/sweep_tables.hpp"

namespace aosuite::ao {
namespace {

namespace rd = aosuite::renderer;

// One plot per resolution: each configuration's mean time and mean RMSE over scenes and views,
// against the reference at the technique's radius or (`unbounded`) against unbounded rays,
// the yardstick common to all radii.
void add_plots(const std::vector<Row>& rows, const std::string& name, bool unbounded,
               std::vector<SweepFile>& files) {
  using Config = std::tuple<rd::Technique, int, float, float>;
  std::map<std::pair<int, int>, std::map<Config, std::tuple<double, double, int>>> sums;
  for (const Row& r : rows) {
    auto& [t, e, n] = sums[{r.width, r.height}][{r.technique, r.samples, r.radius, r.intensity}];
    t += r.gl_ms, e += unbounded ? r.unbounded.rmse : r.error.all.rmse, ++n;
  }
  for (const auto& [res, configs] : sums) {
    std::vector<PlotPoint> points;
    for (const auto& [c, s] : configs) {
      const auto& [t, e, n] = s;
      const auto [tech, samples, radius, intensity] = c;
      points.push_back(
          {std::string(rd::technique_name(tech)), std::max(t / n, 1e-3), e / n,
           fmt::format("{} s={} r={:g} k={:g}: {:.1f} ms, RMSE {:.4f}", rd::technique_name(tech),
                       samples, radius, intensity, t / n, e / n)});
    }
    const std::string svg = pareto_svg(
        points,
        fmt::format("{}: AO time vs RMSE at {}x{} (mean over scenes and views)", name, res.first,
                    res.second),
        "AO passes, median GPU ms (log scale)",
        unbounded ? "RMSE vs ray-traced AO (unbounded)" : "RMSE vs ray-traced AO (radius r)");
    files.push_back(
        {fmt::format("sweep_{}x{}{}.svg", res.first, res.second, unbounded ? "_unbounded" : ""),
         svg});
  }
}

}  // namespace

SweepReport sweep_report(const SweepResult& sweep, const std::string& shard) {
  const SweepMeta& m = sweep.meta;
  SweepReport report;
  report.files.push_back({"sweep.csv", sweep_csv(sweep.rows, m.unbounded)});
  nlohmann::ordered_json j = meta_json(m);
  if (!shard.empty()) j["shard"] = shard;
  j["rows"] = nlohmann::ordered_json::array();
  for (const Row& r : sweep.rows) j["rows"].push_back(row_json(r, m.unbounded));
  j["fit_on_one_view"] = fit_on_one_view(sweep.rows);
  report.files.push_back({"sweep.json", j.dump(2) + "\n"});
  report.files.push_back(
      {"sweep.md", sweep_markdown(sweep.rows, j["fit_on_one_view"], m.unbounded)});
  add_plots(sweep.rows, m.grid, false, report.files);
  if (m.unbounded) add_plots(sweep.rows, m.grid, true, report.files);
  report.fit = j["fit_on_one_view"];
  return report;
}

}  // namespace aosuite::ao

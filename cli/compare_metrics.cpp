#include "cli/compare_metrics.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "common/thread_beside.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"

namespace aosuite::cli {

MetricPlan plan_metrics(const std::vector<std::string>& names,
                        const std::vector<std::string>& gates, const std::string& heatmap) {
  MetricPlan plan;
  // Resemble is the default comparison only when no metric is named in any way.
  plan.resemble = names.empty() && gates.empty() && heatmap.empty();
  for (const std::string& n : names) {
    if (n == "resemble") {
      plan.resemble = true;
    } else {
      metric::gates_for(plan.metrics, metric::find(n));
    }
  }
  for (const std::string& spec : gates) metric::add_gate_spec(plan.metrics, spec);
  plan.heatmap = heatmap;
  if (!heatmap.empty()) metric::gates_for(plan.metrics, metric::heatmap_metric());
  return plan;
}

MetricRun run_metrics(const MetricPlan& plan, const std::string& a, const std::string& b,
                      std::uint64_t max_bytes, RgbaImage* heatmap) {
  MetricRun run;
  if (plan.metrics.empty()) return run;
  // Both files at once: decoding is most of a metric's run for EXR and large PNGs.
  Picture pa, pb;
  side_by_side([&] { pb = read_picture(b, max_bytes); }, [&] { pa = read_picture(a, max_bytes); });
  for (const metric::Gates& g : plan.metrics) {
    const bool map = heatmap && g.metric->heatmap;
    metric::Measurement m = metric::measure(
        *g.metric, pa, pb, {.want_map = map, .tool_pooling = plan.flip_tool_pooling});
    run.json[std::string(g.metric->name)] = m.json();
    std::string line = std::string(g.metric->name) + ":";
    for (const metric::Value& v : m.values)
      line += m.tool_decimals ? fmt::format(" {} {:.{}f}", v.key, v.value, m.tool_decimals)
                              : fmt::format(" {} {:.6g}", v.key, v.value);
    if (m.nonfinite) line += fmt::format(" ({} NaN/Inf pixels)", m.nonfinite);
    run.lines.push_back(line);
    for (metric::Outcome& o : metric::judge(g, m)) run.outcomes.push_back(std::move(o));
    if (map) *heatmap = std::move(m.map);
  }
  return run;
}

}  // namespace aosuite::cli

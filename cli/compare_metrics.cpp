#include "cli/compare_metrics.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace aosuite::cli {

comparison::Tolerance tolerance_from(const ToleranceFlags& flags) {
  comparison::Tolerance t;
  if (!flags.mode.empty() && flags.mode != "default") t.mode = resemble::parse_mode(flags.mode);
  t.max_mismatch_percent = flags.threshold;
  for (const std::string& spec : flags.limits) {
    const std::size_t eq = spec.find('=');
    if (eq == std::string::npos)
      throw std::invalid_argument("--limit '" + spec + "' is not KEY=VALUE");
    comparison::set_limit(t, spec.substr(0, eq), spec.substr(eq + 1));
  }
  // Named metrics are measured (an entry without limits); Resemble's gate stays in force.
  for (const std::string& list : flags.metrics) {
    std::size_t pos = 0;
    while (pos <= list.size()) {
      const std::size_t comma = std::min(list.find(',', pos), list.size());
      const std::string name = list.substr(pos, comma - pos);
      if (name != "resemble") metric::gates_for(t.gates, metric::find(name));
      pos = comma + 1;
    }
  }
  for (const std::string& spec : flags.gates) metric::add_gate_spec(t.gates, spec);
  if (!flags.heatmap.empty()) metric::gates_for(t.gates, metric::heatmap_metric());
  return t;
}

std::vector<std::string> metric_lines(const comparison::Comparison& c) {
  std::vector<std::string> out;
  for (const metric::Measurement& m : c.measured) {
    std::string line = m.metric + ":";
    for (const metric::Value& v : m.values)
      line += m.tool_decimals ? fmt::format(" {} {:.{}f}", v.key, v.value, m.tool_decimals)
                              : fmt::format(" {} {:.6g}", v.key, v.value);
    if (m.nonfinite) line += fmt::format(" ({} NaN/Inf pixels)", m.nonfinite);
    out.push_back(std::move(line));
  }
  return out;
}

}  // namespace aosuite::cli

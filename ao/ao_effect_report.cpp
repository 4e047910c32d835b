#include "ao/ao_effect_report.hpp"

#include <fmt/format.h>

#include <chrono>
#include <map>
#include <vector>

#include "harness/escape.hpp"

namespace aosuite::ao {
namespace {

namespace fs = std::filesystem;
using harness::CaseResult, harness::RunResults, harness::Status, harness::escape_markup;

// The technique a rendered case's labels name.
std::string technique_of(const CaseResult& c) {
  for (const auto& [label, value] : c.labels)
    if (label == "technique") return value;
  return "";
}

// The thesis's Tables 11-14: per technique, how much of the image AO changes.
std::string ao_effect_table(const RunResults& run) {
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> by;
  for (const CaseResult& c : run.cases) {
    if (c.status == Status::kError || c.kind != "render" || !c.figures.count("ao_effect_less"))
      continue;
    by[technique_of(c)].first.push_back(c.figures.at("ao_effect_less"));
    by[technique_of(c)].second.push_back(c.figures.at("ao_effect_nothing"));
  }
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0 : s / static_cast<double>(v.size());
  };
  std::string h =
      "<table><tr><th>technique</th><th>cases</th><th>ignoreLess mismatch %</th>"
      "<th>ignoreNothing mismatch %</th></tr>\n";
  for (const auto& [t, v] : by) {
    h += fmt::format(
        "<tr><td>{}</td><td class=num>{}</td><td class=num>{:.2f}</td>"
        "<td class=num>{:.2f}</td></tr>\n",
        escape_markup(t), v.first.size(), mean(v.first), mean(v.second));
  }
  return h + "</table>\n";
}

// The latest `aosuite sweep` beside this report (its default output, reports/sweep, next to
// reports/<suite>): linked, not embedded, since it is a separate run with its own date.
std::string sweep_link(const fs::path& report_dir) {
  const fs::path sweep = report_dir / ".." / "sweep";
  std::error_code ec;
  const auto when = fs::last_write_time(sweep / "sweep.md", ec);
  if (ec) {
    return "<p>No sweep next to this report yet: <code>aosuite sweep suites/sweep_ci.toml --out "
           "reports/sweep</code> measures each technique's run time against its error.</p>\n";
  }
  const auto age =
      std::chrono::duration_cast<std::chrono::hours>(fs::file_time_type::clock::now() - when);
  std::string links =
      "<a href=\"../sweep/sweep.md\">table</a>, <a href=\"../sweep/sweep.csv\">CSV</a>";
  for (const fs::directory_entry& e : fs::directory_iterator(sweep, ec)) {
    if (e.path().extension() != ".svg") continue;
    const std::string name = escape_markup(e.path().filename().string());
    links += fmt::format(", <a href=\"../sweep/{0}\">{0}</a>", name);
  }
  return fmt::format("<p>Latest sweep ({} h old): {}.</p>\n", age.count(), links);
}

}  // namespace

std::string ao_effect_section(const RunResults& run, const fs::path& report_dir) {
  return "<h2>How much AO changes the image (thesis Tables 11–14)</h2>\n" + ao_effect_table(run) +
         "<h2>Run time against error</h2>\n" + sweep_link(report_dir);
}

}  // namespace aosuite::ao

#include "harness/junit.hpp"

#include <fmt/format.h>

#include "harness/escape.hpp"
#include "harness/runner.hpp"
#include "image/image_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

namespace {

// Where a person reviews a case: the report's panel for it, and its images as the
// [[ATTACHMENT|path]] lines that Jenkins' and GitLab's JUnit readers turn into links.
std::string review(const CaseResult& c, const fs::path& report_dir) {
  const fs::path dir = fs::absolute(report_dir).lexically_normal();
  std::string out = "report: " + escape_markup(report_panel(report_dir, c.id)) + "\n";
  for (const auto& [image, rel] : c.files)
    out += "[[ATTACHMENT|" + escape_markup((dir / "cases" / rel).string()) + "]]\n";
  return out;
}

}  // namespace

void write_junit(const RunResults& run, const fs::path& file, const fs::path& report_dir) {
  const Counts n = count(run);
  double seconds = 0;
  std::string cases;
  for (const CaseResult& c : run.cases) {
    seconds += c.seconds;
    cases += fmt::format(R"(  <testcase classname="{}" name="{}" time="{:.3f}")",
                         escape_markup("aosuite." + run.suite), escape_markup(c.id), c.seconds);
    // Accepting what the report shows (bless --from-report), not a new render of the case.
    const bool approvable = awaits_approval(c.status) && !run.approve_prefix.empty();
    const std::string why =
        escape_markup(c.message + (approvable ? "; to accept what the report shows: " +
                                                    bless_command(run.approve_prefix, {c.id})
                                              : ""));
    const std::string out = "\n    <system-out>" + review(c, report_dir) + "</system-out>";
    switch (c.status) {
      case Status::kPass:
        cases += "/>\n";
        break;
      case Status::kFlaky:  // passed in the end; the failure is kept as Surefire does
        cases += fmt::format(">\n    <flakyFailure message=\"{}\"/>{}\n  </testcase>\n", why, out);
        break;
      case Status::kWarn:  // JUnit has no warning: a pass that says so, where CI servers show it
        cases += fmt::format(">\n    <system-out>WARN: {}\n{}</system-out>\n  </testcase>\n", why,
                             review(c, report_dir));
        break;
      case Status::kFail:
      case Status::kNew:
        cases += fmt::format(">\n    <failure type=\"{}\" message=\"{}\"/>{}\n  </testcase>\n",
                             status_name(c.status), why, out);
        break;
      case Status::kError:
        cases += fmt::format(">\n    <error message=\"{}\"/>{}\n  </testcase>\n", why, out);
        break;
    }
  }
  const std::string xml = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"{}\" "
      "tests=\"{}\" failures=\"{}\" errors=\"{}\" time=\"{:.3f}\">\n{}</testsuite>\n"
      "</testsuites>\n",
      escape_markup(run.suite), run.cases.size(), n.fail + n.fresh, n.error, seconds, cases);
  if (file.has_parent_path()) fs::create_directories(file.parent_path());
  write_text(file, xml);
}

}  // namespace aosuite::harness

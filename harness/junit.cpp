#include "harness/junit.hpp"

#include <fmt/format.h>

#include "harness/escape.hpp"
#include "image/image_io.hpp"

namespace aosuite::harness {

void write_junit(const RunResults& run, const std::filesystem::path& file) {
  const Counts n = count(run);
  double seconds = 0;
  std::string cases;
  for (const CaseResult& c : run.cases) {
    seconds += c.seconds;
    cases += fmt::format(R"(  <testcase classname="{}" name="{}" time="{:.3f}")",
                         escape_markup("aosuite." + run.suite), escape_markup(c.id), c.seconds);
    const std::string why = escape_markup(
        c.message + (c.bless_command.empty() ? "" : "; to accept: " + c.bless_command));
    switch (c.status) {
      case Status::kPass:
        cases += "/>\n";
        break;
      case Status::kFlaky:  // passed in the end; the failure is kept as Surefire does
        cases += fmt::format(">\n    <flakyFailure message=\"{}\"/>\n  </testcase>\n", why);
        break;
      case Status::kWarn:  // JUnit has no warning: a pass that says so, where CI servers show it
        cases += fmt::format(">\n    <system-out>WARN: {}</system-out>\n  </testcase>\n", why);
        break;
      case Status::kFail:
      case Status::kNew:
        cases += fmt::format(">\n    <failure type=\"{}\" message=\"{}\"/>\n  </testcase>\n",
                             status_name(c.status), why);
        break;
      case Status::kError:
        cases += fmt::format(">\n    <error message=\"{}\"/>\n  </testcase>\n", why);
        break;
    }
  }
  const std::string xml = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"{}\" "
      "tests=\"{}\" failures=\"{}\" errors=\"{}\" time=\"{:.3f}\">\n{}</testsuite>\n"
      "</testsuites>\n",
      escape_markup(run.suite), run.cases.size(), n.fail + n.fresh, n.error, seconds, cases);
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  write_text(file, xml);
}

}  // namespace aosuite::harness

#include "harness/github.hpp"

#include <fmt/format.h>

#include "harness/escape.hpp"
#include "harness/html_report.hpp"
#include "harness/runner.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

namespace {

// `s` made printable, with each character `escaped` names replaced by its text.
template <typename Escaped>
std::string escape_with(std::string_view s, Escaped escaped) {
  std::string out;
  for (const char ch : printable(s)) {
    const std::string_view e = escaped(ch);
    if (e.empty()) {
      out += ch;
    } else {
      out += e;
    }
  }
  return out;
}

// A workflow command's message: %, CR and LF escaped (@actions/core's escapeData); a property
// also escapes : and , (escapeProperty).
std::string_view data_escape(char ch) {
  switch (ch) {
    case '%':
      return "%25";
    case '\r':
      return "%0D";
    case '\n':
      return "%0A";
    default:
      return {};
  }
}
std::string_view property_escape(char ch) {
  switch (ch) {
    case ':':
      return "%3A";
    case ',':
      return "%2C";
    default:
      return data_escape(ch);
  }
}
std::string escape_data(std::string_view s) { return escape_with(s, data_escape); }
std::string escape_property(std::string_view s) { return escape_with(s, property_escape); }

// A table cell: one line, | escaped.
std::string cell(std::string_view s) {
  return escape_with(s, [](char ch) -> std::string_view {
    if (ch == '|') return "\\|";
    return ch == '\n' || ch == '\r' ? " " : "";
  });
}

// The file an annotation is on: folder mode's actual image, else the suite file; relative to
// the current folder (the workflow's workspace) where it lies below it, as GitHub matches them.
std::string annotated_file(const RunResults& run, const CaseResult& c) {
  if (run.suite_file.empty()) return "";
  fs::path file = run.suite_file;
  if (!run.expected_folder.empty()) file /= c.source;
  std::error_code ec;
  const fs::path here = fs::current_path(ec);
  const fs::path relative = ec ? fs::path() : file.lexically_relative(here);
  const bool below = !relative.empty() && *relative.begin() != "..";
  return (below ? relative : file).string();
}

// The largest difference of the case's images ("image: 42 @ (200, 152)"), as the terminal
// line gives it; "" where none was measured (new, deleted, could not be judged).
std::string largest_difference(const CaseResult& c) {
  std::string out;
  for (const ImageVerdict& v : c.images) {
    const std::string at = v.largest.text();
    if (!at.empty()) out += (out.empty() ? "" : "; ") + v.image + ": " + at;
  }
  return out;
}

}  // namespace

std::string github_annotations(const RunResults& run, const fs::path& report_dir) {
  std::string out;
  for (const CaseResult& c : run.cases) {
    if (c.status == Status::kPass) continue;
    const bool error = awaits_approval(c.status) || c.status == Status::kError;
    const std::string file = annotated_file(run, c);
    const std::string where = file.empty() ? "" : "file=" + escape_property(file) + ",";
    std::string text = c.id + ": " + c.message + " (report: " + report_panel(report_dir, c.id);
    if (awaits_approval(c.status) && !run.approve_prefix.empty())
      text += "; to accept what the report shows: " + bless_command(run.approve_prefix, {c.id});
    out += fmt::format("::{} {}title={}::{})\n", error ? "error" : "warning", where,
                       escape_property(fmt::format("aosuite {} {}", status_name(c.status), c.id)),
                       escape_data(text));
  }
  return out;
}

std::string github_step_summary(const RunResults& run, const fs::path& report_dir) {
  const Counts n = count(run);
  std::string out = fmt::format(
      "### aosuite: {} — {} case{}: {} passed, {} failed, {} new, {} error{}{}{}\n\n",
      cell(run.suite), run.cases.size(), run.cases.size() == 1 ? "" : "s", n.pass, n.fail, n.fresh,
      n.error, n.error == 1 ? "" : "s", n.flaky ? fmt::format(", {} flaky", n.flaky) : "",
      n.warn ? fmt::format(", {} with warnings", n.warn) : "");
  constexpr int kRows = 50;
  int rows = 0, more = 0;
  std::string table = "| case | status | largest difference | why |\n| --- | --- | --- | --- |\n";
  for (const CaseResult& c : run.cases) {
    if (c.status == Status::kPass) continue;
    if (rows++ >= kRows) {
      ++more;
      continue;
    }
    table += fmt::format("| {} | {} | {} | {} |\n", cell(c.id), status_name(c.status),
                         cell(largest_difference(c)), cell(c.message));
  }
  if (rows > 0) out += table + (more ? fmt::format("\n…and {} more.\n", more) : "") + "\n";
  out += fmt::format("Report: `{}` ({})\n", cell(report_page(report_dir)), report_size(report_dir));
  if (n.fail + n.fresh > 0 && !run.bless_prefix.empty()) {
    out += "\nTo accept what the report shows: `" +
           cell(accept_report_command(run.bless_prefix, report_dir)) + "`\n";
  }
  return out + "\n";
}

}  // namespace aosuite::harness

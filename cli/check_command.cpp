// `aosuite check`, `aosuite bless` and `aosuite report merge`: the harness on the command line.
#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <utility>

#include "cli/commands.hpp"
#include "common/folder_lock.hpp"
#include "harness/escape.hpp"
#include "harness/github.hpp"
#include "harness/html_report.hpp"
#include "harness/junit.hpp"
#include "harness/report_merge.hpp"
#include "harness/runner.hpp"
#include "harness/suite_file.hpp"
#include "image/image_io.hpp"

namespace aosuite::cli {
namespace {

// Prints to stdout, going on when its reader has gone (`aosuite bless | head -1`): SIGPIPE is
// ignored (main.cpp), so the run goes on to its end and only what it prints is lost.
template <typename... T>
void say(fmt::format_string<T...> format, T&&... args) {
  const std::string text = fmt::format(format, std::forward<T>(args)...);
  (void)!std::fwrite(text.data(), 1, text.size(), stdout);
}

namespace fs = std::filesystem;
namespace hs = aosuite::harness;

struct HarnessArgs {
  std::string suite, filter, shard, report, junit, tag, goldens, actual, expected;
  int jobs = 1, retries = 0;
  std::optional<double> max_mismatch;
  std::optional<int> max_channel_delta;
  std::vector<std::string> gates, float_gates, limits;
  std::optional<double> warn_mismatch;  // folder mode's warning tier
  std::vector<std::string> warn_gates;
  bool diff_all = false, no_reuse = false, platform = false, list = false, json = false;
  bool force = false, from_report = false, failed = false, single_file = false;
  bool wait = false;  // for a folder another run holds, instead of failing at once
  std::string annotations = "auto";
  std::string report_images;  // all|failures; empty: failures under CI, else all
  // bless --failed/--from-report with no suite named: the suite name the report's results.json
  // gives, which the suite file it names must carry too.
  std::string report_suite;
};

void add_annotations_option(CLI::App* cmd, std::string& annotations) {
  cmd->add_option("--annotations", annotations,
                  "github: ::error/::warning lines and a Markdown table appended to "
                  "$GITHUB_STEP_SUMMARY; none; auto (default): github under GitHub Actions")
      ->option_text("auto|github|none")
      ->check(CLI::IsMember({"auto", "github", "none"}));
}

void add_selection_options(CLI::App* cmd, HarnessArgs& a) {
  cmd->add_option("suite", a.suite, "suite file, e.g. suites/default.toml")->option_text("SUITE");
  cmd->add_option("--actual", a.actual,
                  "folder mode, without a suite: the new images (image files, by relative path)")
      ->option_text("DIR");
  cmd->add_option("--expected", a.expected,
                  "folder mode: the accepted images, paired with --actual by relative path")
      ->option_text("DIR");
  cmd->add_option("--max-mismatch", a.max_mismatch,
                  "folder mode: allowed Resemble mismatch % per image (default 0); every other "
                  "limit stays")
      ->option_text("0..100")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--max-channel-delta", a.max_channel_delta,
                  "folder mode: the largest |new - golden| of any channel still passing "
                  "(default 8; 255 lifts it)")
      ->option_text("0..255")
      ->check(CLI::Range(0, 255));
  cmd->add_option("--limit", a.limits,
                  "folder mode: KEY=VALUE, any limit a suite's [tolerance] sets, e.g. "
                  "max_mean_shift=1, shift_radius=1, allow_kind_change=true (repeatable)")
      ->option_text("KEY=VALUE");
  cmd->add_option("--gate", a.gates,
                  "folder mode: METRIC.KEY=VALUE, as in `compare --gate` (e.g. flip.max_mean=0.02; "
                  "repeatable), beside Resemble's gate, for every image")
      ->option_text("METRIC.KEY=VALUE");
  cmd->add_option("--float-gate", a.float_gates,
                  "folder mode: METRIC.KEY=VALUE for float images only (EXR, HDR, float TIFF); "
                  "without one they must be byte-identical")
      ->option_text("METRIC.KEY=VALUE");
  cmd->add_option("--warn-max-mismatch", a.warn_mismatch,
                  "folder mode: a passing image above this Resemble mismatch % is a WARN (exit 0)")
      ->option_text("0..100")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--warn-gate", a.warn_gates,
                  "folder mode: METRIC.KEY=VALUE, a gate a passing image may break with a WARN "
                  "(exit 0), e.g. flip.max_mean=0.005; repeatable")
      ->option_text("METRIC.KEY=VALUE");
  cmd->add_option("--filter", a.filter,
                  "only cases whose id contains a match of this regular expression (anchor it, "
                  "'^id$', for exactly one case)")
      ->option_text("REGEX");
  cmd->add_option("--goldens", a.goldens,
                  "goldens folder (default: the suite's goldens key, else goldens/<suite name> "
                  "in the current directory)")
      ->option_text("DIR");
  cmd->add_option("--shard", a.shard,
                  "i/n: run every n-th case from the i-th (default: GTEST_SHARD_INDEX / "
                  "GTEST_TOTAL_SHARDS when set)")
      ->option_text("I/N");
  cmd->add_option("--jobs,-j", a.jobs,
                  "cases run at once (default 1); a scene case renders in a GL context of its own")
      ->option_text("N");
  cmd->add_option("--report", a.report, "report folder (default: reports/<suite name>)")
      ->option_text("DIR");
  cmd->add_flag("--no-reuse", a.no_reuse, "re-render and re-judge even unchanged cases");
  cmd->add_flag("--wait", a.wait,
                "wait for another aosuite that is writing the same report or goldens folder "
                "(default: fail at once, naming it)");
}

hs::Suite load(const HarnessArgs& a) {
  const bool folders = !a.actual.empty() || !a.expected.empty();
  if (folders && (a.actual.empty() || a.expected.empty())) {
    throw std::invalid_argument("folder mode needs both --actual DIR and --expected DIR");
  }
  if (folders == !a.suite.empty()) {
    throw std::invalid_argument(folders ? "give a suite file or --actual/--expected, not both"
                                        : "give a suite file, or --actual DIR --expected DIR");
  }
  if (!folders &&
      (a.max_mismatch || a.max_channel_delta || !a.gates.empty() || !a.float_gates.empty() ||
       !a.limits.empty() || a.warn_mismatch || !a.warn_gates.empty())) {
    throw std::invalid_argument(
        "--max-mismatch, --max-channel-delta, --limit, --gate, --float-gate and --warn-* are "
        "folder mode's; a suite says its tolerances itself");
  }
  if (folders) {
    if (!a.goldens.empty() || a.platform || !a.tag.empty()) {
      throw std::invalid_argument(
          "folder mode takes no --goldens, --platform or --variant: --expected holds the goldens");
    }
    // The one tolerance: each flag sets the limit it names, every other keeps its default.
    hs::Tolerance t;
    if (a.max_mismatch) t.max_mismatch_percent = *a.max_mismatch;
    if (a.max_channel_delta) t.max_channel_delta = *a.max_channel_delta;
    for (const std::string& spec : a.limits) {
      const std::size_t eq = spec.find('=');
      if (eq == std::string::npos) {
        throw std::invalid_argument("--limit '" + hs::printable(spec) + "' is not KEY=VALUE");
      }
      comparison::set_limit(t, spec.substr(0, eq), spec.substr(eq + 1));
    }
    for (const std::string& spec : a.gates) metric::add_gate_spec(t.gates, spec);
    for (const std::string& spec : a.float_gates) metric::add_gate_spec(t.float_gates, spec);
    if (a.warn_mismatch) t.warn.max_mismatch_percent = *a.warn_mismatch;
    for (const std::string& spec : a.warn_gates) metric::add_gate_spec(t.warn.gates, spec);
    return hs::folder_suite(a.actual, a.expected, t);
  }
  hs::Suite suite = hs::load_suite(a.suite);
  if (!a.goldens.empty()) suite.goldens = a.goldens, suite.goldens_given = true;
  return suite;
}

hs::RunOptions run_options(const hs::Suite& suite, const HarnessArgs& a) {
  hs::RunOptions o;
  o.selection.filter = a.filter;
  hs::set_shard(o.selection, a.shard);
  o.jobs = a.jobs;
  o.report_dir = a.report.empty() ? fs::path("reports") / suite.name : fs::path(a.report);
  o.diff_all = a.diff_all;
  // Under CI the report is an artifact someone downloads: only what needs a reviewer's eyes.
  const char* ci = std::getenv("CI");
  const bool under_ci = ci && *ci && std::string_view(ci) != "false";
  const std::string images = !a.report_images.empty()  ? a.report_images
                             : under_ci && !a.diff_all ? "failures"
                                                       : "all";
  if (images == "failures" && a.diff_all) {
    throw std::invalid_argument(
        "--diff-all writes passing cases' diffs, which --report-images failures leaves out");
  }
  o.passing_images = images == "all";
  o.reuse = !a.no_reuse;
  o.retries = a.retries;
  return o;
}

void print_progress(const hs::CaseResult& r, int done, int total) {
  std::string detail;
  for (const hs::ImageVerdict& v : r.images) {
    detail += "  " + v.image;
    // Resemble's mismatch and largest channel difference where its gate holds (or nothing else
    // was measured), then each gate, named by its region; nothing where nothing was measured.
    if (r.tolerance.resemble && v.comparable && !v.mismatch_text.empty()) {
      detail += fmt::format(" {}%", v.mismatch_text);
    }
    // How much and where it differs most (idiff's "max error @ (x, y)"), float images too.
    if (!v.largest.text().empty()) detail += " max Δ " + v.largest.text();
    for (const metric::Outcome& o : v.outcomes) {
      detail += fmt::format(" {}{} {} {:.4g}", o.region.empty() ? "" : o.region + ": ", o.metric,
                            o.stat, o.value);
    }
    if (v.identical) detail += " (identical)";
  }
  if (r.status != hs::Status::kPass && !r.message.empty()) detail += "  " + r.message;
  for (const hs::ImageVerdict& v : r.images) {
    if (!v.changes.empty())
      detail += "  " + v.image + " changed: " + comparison::changes_text(v.changes, 2);
  }
  if (r.kind == "folder") detail = "  " + r.source + detail;
  say("[{:>{}}/{}] {:<5} {}{}  {:.2f} s{}{}\n", done, fmt::formatted_size("{}", total), total,
      hs::status_name(r.status), r.id, hs::printable(detail), r.seconds,
      r.reused               ? " (unchanged, reused)"
      : r.not_reused.empty() ? ""
                             : " (" + r.not_reused + ")",
      r.attempts > 1 ? fmt::format(" ({} attempts)", r.attempts) : "");
  std::fflush(stdout);
}

// The GoogleTest sharding protocol: a runner that honours the shard variables says so by
// touching this file (Bazel checks for it).
void acknowledge_sharding() {
  if (const char* f = std::getenv("GTEST_SHARD_STATUS_FILE"); f && *f) {
    std::FILE* touch = std::fopen(f, "a");
    if (touch) std::fclose(touch);
  }
}

struct Output {
  bool json = false;
  bool single_file = false;
  const std::vector<hs::Skipped>* skipped = nullptr;  // folder mode's files that are no case
  std::string annotations = "auto";  // github, none, or auto: github under GitHub Actions
};

// "a.txt (not an image file), loop.png (a symbolic link (not followed)), and 3 more"
std::string skipped_text(const std::vector<hs::Skipped>& skipped) {
  std::string out;
  constexpr std::size_t kShown = 10;
  for (std::size_t i = 0; i < skipped.size() && i < kShown; ++i)
    out += fmt::format("{}{} ({})", i ? ", " : "", skipped[i].path, skipped[i].why);
  if (skipped.size() > kShown) out += fmt::format(", and {} more", skipped.size() - kShown);
  return hs::printable(out);
}

// Budgets that passing images use under a tenth of (ImageVerdict::stale): one line, the first
// few named, so tolerances tighten over time instead of hiding the next change.
void print_stale(const hs::RunResults& run) {
  std::vector<std::string> named;
  std::size_t images = 0;
  for (const hs::CaseResult& c : run.cases) {
    for (const hs::ImageVerdict& v : c.images) {
      if (v.stale.empty()) continue;
      ++images;
      if (named.size() < 3)
        named.push_back(fmt::format("{} {}: {}", c.id, v.image, v.stale.front()));
    }
  }
  if (!images) return;
  std::string list;
  for (const std::string& n : named) list += (list.empty() ? "" : "; ") + n;
  say("stale budgets: {} passing image{} use under a tenth of a limit ({}{}; results.json "
      "\"stale\" lists them)\n",
      images, images == 1 ? "" : "s", hs::printable(list), images > named.size() ? "; ..." : "");
}

// On GitHub Actions: annotations on stdout (not among --json's lines, which must stay JSON) and
// the step summary appended to $GITHUB_STEP_SUMMARY. A summary that cannot be written is a
// warning: the verdict stands.
void speak_github(const hs::RunResults& run, const fs::path& report_dir, bool json) {
  if (!json) say("{}", hs::github_annotations(run, report_dir));
  const char* summary = std::getenv("GITHUB_STEP_SUMMARY");
  if (!summary || !*summary) return;
  std::ofstream file(summary, std::ios::app);
  file << hs::github_step_summary(run, report_dir);
  file.flush();
  if (!file) {
    fmt::print(stderr, "aosuite: warning: {}: cannot append the step summary\n",
               hs::printable(summary));
  }
}

int finish(const hs::RunResults& run, const fs::path& report_dir, const std::string& junit,
           const Output& out) {
  hs::write_html_report(run, report_dir, {.single_file = out.single_file});
  if (!junit.empty()) hs::write_junit(run, junit, report_dir);
  const char* actions = std::getenv("GITHUB_ACTIONS");
  if (out.annotations == "github" ||
      (out.annotations == "auto" && actions && std::string_view(actions) == "true")) {
    speak_github(run, report_dir, out.json);
  }
  const hs::Counts n = hs::count(run);
  std::vector<std::string> to_accept;
  for (const hs::CaseResult& c : run.cases) {
    if (!c.bless_command.empty()) to_accept.push_back(c.id);
  }
  const std::string accept_all = to_accept.empty() || run.bless_prefix.empty()
                                     ? std::string()
                                     : hs::bless_command(run.bless_prefix, to_accept);
  const std::string report = (report_dir / "index.html").string();
  if (out.json) {
    const nlohmann::json summary = {
        {"type", "summary"},
        {"suite", run.suite},
        {"cases", run.cases.size()},
        {"passed", n.pass},
        {"failed", n.fail},
        {"new", n.fresh},
        {"errors", n.error},
        {"flaky", n.flaky},
        {"warnings", n.warn},
        {"exit_status", hs::exit_code(n)},
        {"report", hs::printable(report)},
        {"results", hs::printable((report_dir / "results.json").string())},
        {"report_size", hs::report_size(report_dir)},
        {"bless_command", hs::printable(accept_all)},
        {"skipped", out.skipped ? out.skipped->size() : 0},
        {"approve_failed", to_accept.empty() ? std::string()
                                             : hs::printable(hs::accept_report_command(
                                                   run.bless_prefix, report_dir))}};
    say("{}\n", summary.dump());
    std::fflush(stdout);
    return hs::exit_code(n);
  }
  const std::string flaky = (n.flaky ? fmt::format(", {} flaky", n.flaky) : "") +
                            (n.warn ? fmt::format(", {} with warnings", n.warn) : "");
  if (out.skipped && !out.skipped->empty()) {
    say("skipped {} file{}: {}\n", out.skipped->size(), out.skipped->size() == 1 ? "" : "s",
        skipped_text(*out.skipped));
  }
  if (!run.cases.empty() && run.cases.front().kind == "folder") {
    say("{} image{}: {} unchanged, {} changed, {} new, {} deleted, {} error{}{}. Report: {} ({})\n",
        run.cases.size(), run.cases.size() == 1 ? "" : "s", n.pass, n.fail - n.deleted, n.fresh,
        n.deleted, n.error, n.error == 1 ? "" : "s", flaky, hs::printable(report),
        hs::report_size(report_dir));
  } else {
    say("{} case{}: {} passed, {} failed, {} new, {} error{}{}. Report: {} ({})\n",
        run.cases.size(), run.cases.size() == 1 ? "" : "s", n.pass, n.fail, n.fresh, n.error,
        n.error == 1 ? "" : "s", flaky, hs::printable(report), hs::report_size(report_dir));
  }
  print_stale(run);
  for (const hs::CaseResult& c : run.cases) {
    if (c.bless_command.empty()) continue;
    say("  to accept {}: {}\n", c.id, hs::printable(c.bless_command));
  }
  if (to_accept.size() > 1 && !accept_all.empty()) {
    say("  to accept all {} failing{} and new cases: {}\n", to_accept.size(),
        n.warn ? ", warning" : "", hs::printable(accept_all));
  }
  if (!to_accept.empty() && !run.bless_prefix.empty()) {
    say("  or review {} and accept the images it shows: {}\n", hs::printable(report),
        hs::printable(hs::accept_report_command(run.bless_prefix, report_dir)));
  }
  std::fflush(stdout);
  return hs::exit_code(n);
}

int run_check(const HarnessArgs& a) {
  const hs::Suite suite = load(a);
  if (!a.actual.empty() && suite.cases.empty()) {
    throw std::invalid_argument(fmt::format(
        "no image file under {} or {}{}", hs::printable(a.actual), hs::printable(a.expected),
        suite.skipped.empty()
            ? std::string()
            : fmt::format("; skipped {}: {}", suite.skipped.size(), skipped_text(suite.skipped))));
  }
  hs::RunOptions o = run_options(suite, a);
  if (a.list) {
    const std::vector<const hs::Case*> cases = hs::select(suite, o.selection);
    if (cases.empty()) {
      throw std::invalid_argument(hs::printable(a.suite + ": the selection holds none of its " +
                                                std::to_string(suite.cases.size()) + " cases"));
    }
    for (const hs::Case* c : cases) say("{}\n", c->id);
    return kExitSame;
  }
  if (a.json) {
    // One JSON object per line, per case as it finishes, then the summary.
    o.progress = [](const hs::CaseResult& r, int, int) {
      nlohmann::json j = hs::to_json(r);
      j["type"] = "case";
      say("{}\n", j.dump());
      std::fflush(stdout);
    };
  } else {
    o.progress = print_progress;
  }
  acknowledge_sharding();
  const FolderLock report(o.report_dir, a.wait);  // held until the report is written
  const hs::RunResults run = hs::check(suite, o);
  return finish(run, o.report_dir, a.junit,
                {.json = a.json,
                 .single_file = a.single_file,
                 .skipped = &suite.skipped,
                 .annotations = a.annotations});
}

// `bless --failed --report DIR` (or --from-report) with no suite named: the suite file, or
// folder mode's two folders, the report was made from, as its results.json says (absolute, so
// from any directory).
HarnessArgs with_report_suite(HarnessArgs a) {
  const bool folders = !a.actual.empty() || !a.expected.empty();
  if (!a.suite.empty() || folders || !(a.failed || a.from_report) || a.report.empty()) return a;
  const hs::RunResults last = hs::read_results(a.report);
  if (last.suite_file.empty()) {
    throw std::invalid_argument(fmt::format(
        "{}: names no suite file or folders; name the suite (or --actual DIR --expected DIR)",
        (fs::path(a.report) / "results.json").string()));
  }
  if (!last.expected_folder.empty()) {
    a.actual = last.suite_file, a.expected = last.expected_folder;
  } else {
    a.suite = last.suite_file, a.report_suite = last.suite;
    if (a.goldens.empty()) a.goldens = last.goldens;  // goldens/<name> was cwd-relative
  }
  return a;
}

int run_bless(const HarnessArgs& given) {
  const HarnessArgs a = with_report_suite(given);
  const hs::Suite suite = load(a);
  if (!a.report_suite.empty()) {
    // results.json is only data: the suite file it names must be the suite it was made from.
    if (suite.name != a.report_suite) {
      throw std::invalid_argument(hs::printable(fmt::format(
          "{}: names suite file {}, whose suite is '{}', not '{}'; name the suite to bless",
          (fs::path(a.report) / "results.json").string(), a.suite, suite.name, a.report_suite)));
    }
    say("suite {} (from {})\n", hs::printable(a.suite),
        hs::printable((fs::path(a.report) / "results.json").string()));
  }
  hs::BlessOptions b{.run = run_options(suite, a),
                     .platform = a.platform,
                     .tag = a.tag,
                     .force = a.force,
                     .from_report = a.from_report,
                     .failed = a.failed};
  // One line per case as it finishes, flushed: a redirected log shows what was written even
  // when bless is killed.
  b.run.progress = [](const hs::CaseResult& r, int done, int total) {
    say("[{}/{}] {} {}: {}\n", done, total,
        r.kept                          ? "KEPT"
        : r.status == hs::Status::kPass ? "BLESSED"
                                        : "NOT BLESSED",
        r.id, hs::printable(r.message));
    std::fflush(stdout);
  };
  // The report folder (bless renders into it, or reads what it judged) and then the goldens.
  const FolderLock report(b.run.report_dir, a.wait), goldens(suite.goldens, a.wait);
  const hs::RunResults run = hs::bless(suite, b);
  if (run.cases.empty()) {
    say("nothing to accept: no case failed or is new in {}\n",
        hs::printable((b.run.report_dir / "results.json").string()));
    return kExitSame;
  }
  const hs::Counts n = hs::count(run);
  int kept = 0;
  for (const hs::CaseResult& c : run.cases) kept += c.kept;
  say("{} of {} cases blessed into {}{}{}\n", n.pass - kept, run.cases.size(),
      hs::printable(suite.goldens.string()),
      kept ? fmt::format("; {} passing kept as they were (--force rewrites them)", kept) : "",
      n.error ? fmt::format("; {} not blessed, their goldens as they were (reasons above)", n.error)
              : "");
  std::fflush(stdout);
  return n.error ? kExitError : kExitSame;
}

// The merged report's verdict, printed and written as a run's is.
int run_merge(const std::string& out, const std::vector<std::string>& shards,
              const std::string& junit, bool partial, bool wait, const std::string& annotations) {
  const hs::MergedReport merged = hs::merge_reports(out, shards, partial, wait);
  if (!merged.missing.empty()) {
    fmt::print(stderr, "report merge: a partial run: {} missing\n", merged.missing);
  }
  return finish(merged.run, out, junit, {.annotations = annotations});
}

// Runs `f`, showing an error's bytes that are not printable UTF-8 escaped (a path may hold any).
template <typename F>
int escaped_errors(F f) {
  try {
    return f();
  } catch (const std::exception& e) {
    throw std::runtime_error(hs::printable(e.what()));
  }
}

}  // namespace

void add_check_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<HarnessArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Gate a suite's cases (renders, command outputs, files) or a folder's images against "
      "their goldens, and write the report. Exit status: 0 all passed, 1 a case failed or has "
      "no golden yet, 2 a case could not be made or judged.");
  add_selection_options(cmd, *a);
  cmd->add_option("--junit", a->junit, "also write JUnit XML here")->option_text("FILE");
  cmd->add_flag("--diff-all", a->diff_all, "write diff images for passing cases too");
  cmd->add_option("--report-images", a->report_images,
                  "which cases keep their images in the report: all, or failures (failing, new, "
                  "warning, flaky and unjudged cases; passing ones keep their numbers and their "
                  "goldens' paths). Default: failures when $CI is set, else all")
      ->option_text("all|failures")
      ->check(CLI::IsMember({"all", "failures"}));
  cmd->add_flag("--list", a->list, "print the selected case ids and stop");
  cmd->add_option("--retries", a->retries,
                  "run a failing case up to N more times; one that then passes is FLAKY")
      ->option_text("N")
      ->check(CLI::Range(0, 100));
  cmd->add_flag("--json", a->json,
                "print one JSON object per case as it finishes, then a summary object");
  cmd->add_flag("--single-file", a->single_file,
                "embed the images in index.html (one file to mail; for small suites)");
  add_annotations_option(cmd, a->annotations);
  guarded(cmd, rc, "check", [a] { return escaped_errors([&] { return run_check(*a); }); });
}

void add_bless_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<HarnessArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bless", "Accept the current renders of a suite's cases as their goldens (atomic writes)");
  add_selection_options(cmd, *a);
  cmd->add_flag("--platform", a->platform,
                "write goldens for this GL platform only (goldens/<suite>/<case>/<platform>/)");
  cmd->add_option("--variant", a->tag, "add an accepted variant <image>~<tag>.png instead")
      ->option_text("TAG");
  cmd->add_flag("--force", a->force, "rewrite the goldens of cases that pass too");
  cmd->add_flag("--from-report", a->from_report,
                "accept the last report's images (--report DIR) instead of rendering");
  cmd->add_flag("--failed", a->failed,
                "accept every FAIL, NEW and WARN case of the last report, from its images (with "
                "--report DIR and no suite: the report's own suite)");
  guarded(cmd, rc, "bless", [a] { return escaped_errors([&] { return run_bless(*a); }); });
}

void add_report_command(CLI::App& app, int& rc) {
  CLI::App* cmd = app.add_subcommand("report", "Work with run reports");
  cmd->require_subcommand(1);
  CLI::App* merge = cmd->add_subcommand("merge", "Join shard reports into one report");
  auto out = std::make_shared<std::string>();
  auto junit = std::make_shared<std::string>();
  auto shards = std::make_shared<std::vector<std::string>>();
  merge->add_option("--out", *out, "merged report folder")->required()->option_text("DIR");
  merge->add_option("--junit", *junit, "also write JUnit XML here")->option_text("FILE");
  merge->add_option("shards", *shards, "report folders of the shards")
      ->required()
      ->option_text("DIR...");
  auto partial = std::make_shared<bool>(false), wait = std::make_shared<bool>(false);
  merge->add_flag("--partial", *partial,
                  "merge even when shards of the run are missing; the report says which");
  merge->add_flag("--wait", *wait, "wait for another aosuite writing --out");
  auto annotations = std::make_shared<std::string>("auto");
  add_annotations_option(merge, *annotations);
  guarded(merge, rc, "report merge", [out, shards, junit, partial, wait, annotations] {
    return escaped_errors(
        [&] { return run_merge(*out, *shards, *junit, *partial, *wait, *annotations); });
  });
}

}  // namespace aosuite::cli

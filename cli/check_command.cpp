// `aosuite check`, `aosuite bless` and `aosuite report merge`: the harness on the command line.
#include <fmt/format.h>

#include <filesystem>

#include "cli/commands.hpp"
#include "harness/html_report.hpp"
#include "harness/junit.hpp"
#include "harness/runner.hpp"

namespace aosuite::cli {
namespace {

namespace fs = std::filesystem;
namespace hs = aosuite::harness;

struct HarnessArgs {
  std::string suite, filter, shard, report, junit, tag;
  int jobs = 1;
  bool diff_all = false, no_reuse = false, platform = false, list = false;
};

void add_selection_options(CLI::App* cmd, HarnessArgs& a) {
  cmd->add_option("suite", a.suite, "suite file, e.g. suites/default.toml")->required();
  cmd->add_option("--filter", a.filter, "only cases whose id matches this regular expression");
  cmd->add_option("--shard", a.shard,
                  "i/n: run every n-th case from the i-th (default: GTEST_SHARD_INDEX / "
                  "GTEST_TOTAL_SHARDS when set)");
  cmd->add_option("--jobs,-j", a.jobs, "cases rendered at once, each with its own GL context")
      ->capture_default_str();
  cmd->add_option("--report", a.report, "report folder (default: reports/<suite name>)");
  cmd->add_flag("--no-reuse", a.no_reuse, "re-render and re-judge even unchanged cases");
}

hs::RunOptions run_options(const hs::Suite& suite, const HarnessArgs& a) {
  hs::RunOptions o;
  o.selection.filter = a.filter;
  hs::set_shard(o.selection, a.shard);
  o.jobs = a.jobs;
  o.report_dir = a.report.empty() ? fs::path("reports") / suite.name : fs::path(a.report);
  o.diff_all = a.diff_all;
  o.reuse = !a.no_reuse;
  return o;
}

void print_progress(const hs::CaseResult& r, int done, int total) {
  std::string detail;
  for (const hs::ImageVerdict& v : r.images) {
    detail += fmt::format("  {} {}%{}", v.image, v.mismatch_text.empty() ? "-" : v.mismatch_text,
                          v.identical ? " (identical)" : "");
  }
  if (r.status != hs::Status::kPass && !r.message.empty()) detail += "  " + r.message;
  fmt::print("[{:>{}}/{}] {:<5} {}{}  {:.2f} s{}\n", done, fmt::formatted_size("{}", total), total,
             hs::status_name(r.status), r.id, detail, r.seconds,
             r.reused ? " (unchanged, reused)" : "");
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

int finish(const hs::RunResults& run, const fs::path& report_dir, const std::string& junit) {
  hs::write_html_report(run, report_dir);
  if (!junit.empty()) hs::write_junit(run, junit);
  const hs::Counts n = hs::count(run);
  fmt::print("{} cases: {} passed, {} failed, {} new, {} errors. Report: {}\n", run.cases.size(),
             n.pass, n.fail, n.fresh, n.error, (report_dir / "index.html").string());
  for (const hs::CaseResult& c : run.cases) {
    if (!c.bless_command.empty()) fmt::print("  to accept {}: {}\n", c.id, c.bless_command);
  }
  return hs::exit_code(n);
}

int run_check(const HarnessArgs& a) {
  const hs::Suite suite = hs::load_suite(a.suite);
  hs::RunOptions o = run_options(suite, a);
  if (a.list) {
    for (const hs::Case* c : hs::select(suite, o.selection)) fmt::print("{}\n", c->id);
    return kExitSame;
  }
  o.progress = print_progress;
  acknowledge_sharding();
  const hs::RunResults run = hs::check(suite, o);
  return finish(run, o.report_dir, a.junit);
}

int run_bless(const HarnessArgs& a) {
  const hs::Suite suite = hs::load_suite(a.suite);
  hs::BlessOptions b{.run = run_options(suite, a), .platform = a.platform, .tag = a.tag};
  b.run.progress = [](const hs::CaseResult& r, int done, int total) {
    fmt::print("[{}/{}] {} {}: {}\n", done, total,
               r.status == hs::Status::kPass ? "BLESSED" : "NOT BLESSED", r.id, r.message);
  };
  const hs::RunResults run = hs::bless(suite, b);
  const hs::Counts n = hs::count(run);
  fmt::print(
      "{} goldens blessed into {}, {} cases could not be rendered (their goldens are "
      "untouched)\n",
      n.pass, suite.goldens.string(), n.error);
  return n.error ? kExitError : kExitSame;
}

int run_merge(const std::string& out, const std::vector<std::string>& shards,
              const std::string& junit) {
  hs::RunResults merged;
  for (const std::string& dir : shards) {
    hs::RunResults part = hs::read_results(dir);
    if (merged.suite.empty()) {
      merged = part;
      merged.cases.clear();
    } else if (part.suite != merged.suite) {
      throw std::runtime_error(
          fmt::format("{}: suite '{}' differs from '{}'", dir, part.suite, merged.suite));
    }
    for (hs::CaseResult& c : part.cases) {
      const fs::path from = fs::path(dir) / "cases" / c.id, to = fs::path(out) / "cases" / c.id;
      if (!fs::equivalent(fs::path(dir), fs::path(out))) {
        fs::create_directories(to);
        fs::copy(from, to, fs::copy_options::overwrite_existing | fs::copy_options::recursive);
      }
      merged.cases.push_back(std::move(c));
    }
  }
  merged.shard.clear();
  fs::create_directories(out);
  hs::write_results(out, merged);
  return finish(merged, out, junit);
}

}  // namespace

void add_check_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<HarnessArgs>();
  CLI::App* cmd = app.add_subcommand(
      "check",
      "Render a suite's cases and compare each with its golden. Exit status: 0 all passed, "
      "1 a case failed or has no golden yet, 2 a case could not be rendered or judged.");
  add_selection_options(cmd, *a);
  cmd->add_option("--junit", a->junit, "also write JUnit XML here");
  cmd->add_flag("--diff-all", a->diff_all, "write diff images for passing cases too");
  cmd->add_flag("--list", a->list, "print the selected case ids and stop");
  guarded(cmd, rc, "check", [a] { return run_check(*a); });
}

void add_bless_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<HarnessArgs>();
  CLI::App* cmd = app.add_subcommand(
      "bless", "Accept the current renders of a suite's cases as their goldens (atomic writes)");
  add_selection_options(cmd, *a);
  cmd->add_flag("--platform", a->platform,
                "write goldens for this GL platform only (goldens/<suite>/<case>/<platform>/)");
  cmd->add_option("--variant", a->tag, "add an accepted variant <image>~<tag>.png instead");
  guarded(cmd, rc, "bless", [a] { return run_bless(*a); });
}

void add_report_command(CLI::App& app, int& rc) {
  CLI::App* cmd = app.add_subcommand("report", "Work with run reports");
  cmd->require_subcommand(1);
  CLI::App* merge = cmd->add_subcommand("merge", "Join shard reports into one report");
  auto out = std::make_shared<std::string>();
  auto junit = std::make_shared<std::string>();
  auto shards = std::make_shared<std::vector<std::string>>();
  merge->add_option("--out", *out, "merged report folder")->required();
  merge->add_option("--junit", *junit, "also write JUnit XML here");
  merge->add_option("shards", *shards, "report folders of the shards")->required();
  guarded(merge, rc, "report merge",
          [out, shards, junit] { return run_merge(*out, *shards, *junit); });
}

}  // namespace aosuite::cli

// `aosuite tolerances suggest SUITE --report DIR...`: each case's tolerance that passes every
// given run with a margin a held-back run needed, written into the last report folder for review
// (harness/tolerance_suggest.hpp). With
// no SUITE the reports are folder-mode runs, and the folder-mode flags of the loosest of those
// tolerances are printed: folder mode judges every image by one.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "cli/commands.hpp"
#include "common/file_io.hpp"
#include "harness/escape.hpp"
#include "harness/invocation.hpp"
#include "harness/suggest_toml.hpp"
#include "harness/suite_file.hpp"

namespace aosuite::cli {
namespace {

namespace fs = std::filesystem;
namespace hs = aosuite::harness;

struct SuggestArgs {
  std::string suite, goldens, out;
  std::vector<std::string> reports;
  std::optional<double> margin;
};

// "mismatch 0.5 -> 0.06511 %, max Δ 8 -> 3, flip max_mean 0.02 -> 0.01234": each limit the
// suggestion sets, as the suite has it and as suggested.
std::string limits_text(const hs::Suggestion& s) {
  std::vector<std::string> parts;
  if (s.proposed.resemble) {
    parts.push_back(fmt::format("mismatch {} -> {} %", s.current.max_mismatch_percent,
                                s.proposed.max_mismatch_percent));
    parts.push_back(
        fmt::format("max Δ {} -> {}", s.current.max_channel_delta, s.proposed.max_channel_delta));
  }
  std::vector<double> now;
  hs::for_each_limit(s.current, [&](auto, auto&, auto& l) { now.push_back(l.limit); });
  std::size_t i = 0;
  hs::for_each_limit(s.proposed, [&](std::string_view region, auto& g, auto& l) {
    parts.push_back(fmt::format("{}{} {}_{} {} -> {}",
                                region.empty() ? "" : std::string(region) + ": ", g.metric->name,
                                l.is_max ? "max" : "min", l.stat, now[i++], l.limit));
  });
  return fmt::format("{}", fmt::join(parts, ", "));
}

// Folder mode has no suite file to write beside: the flags that set the one tolerance every
// image passes under are printed.
int finish_folder_mode(const std::vector<hs::Suggestion>& all, const hs::Suite& suite,
                       std::size_t suggested) {
  const std::optional<hs::Tolerance> t = hs::loosest(all);
  fmt::print("folder mode, one tolerance for every image ({} of {} suggested):\n  {} check {} {}\n",
             suggested, all.size(), hs::program_command(), suite.check_args, hs::folder_flags(*t));
  return suggested == all.size() ? kExitSame : kExitDifferent;
}

int run_suggest(const SuggestArgs& a) {
  const std::vector<fs::path> reports(a.reports.begin(), a.reports.end());
  const bool folders = a.suite.empty();
  if (folders && (!a.goldens.empty() || !a.out.empty()))
    throw std::invalid_argument("folder mode takes no --goldens or --out: its flags are printed");
  hs::Suite suite = folders ? hs::folder_suite_of(reports) : hs::load_suite(a.suite);
  if (!a.goldens.empty()) suite.goldens = a.goldens, suite.goldens_given = true;
  const hs::SuggestOptions options{.margin_percent = a.margin};
  const std::vector<hs::Suggestion> all = hs::suggest(suite, reports, options);
  std::size_t width = 4, suggested = 0;
  for (const hs::Suggestion& s : all) width = std::max(width, s.id.size());
  fmt::print("{:<{}}  runs  limits (now -> suggested)\n", "case", width);
  for (const hs::Suggestion& s : all) {
    suggested += s.reason.empty();
    if (!s.reason.empty()) {
      fmt::print("{:<{}}  {:>4}  not suggested: {}\n", s.id, width, s.runs.size(), s.reason);
      continue;
    }
    // The margin under the limits, and the limits it is not on.
    fmt::print("{:<{}}  {:>4}  {}\n{:{}}{}\n", s.id, width, s.runs.size(), limits_text(s), "",
               width + 8, hs::margin_text(s));
    for (const std::string& n : s.margin_notes) fmt::print("{:{}}  {}\n", "", width + 8, n);
  }
  if (suggested == 0) {
    throw std::runtime_error(fmt::format(
        "nothing to suggest: no case of {} has two usable runs in the {} report{} given (reasons "
        "above); nothing written",
        folders ? "the folders" : a.suite, reports.size(), reports.size() == 1 ? "" : "s"));
  }
  if (folders) return finish_folder_mode(all, suite, suggested);
  // A report folder is the run's own, and a file in the goldens folder would read as a golden.
  const fs::path out =
      a.out.empty() ? reports.back() / "tolerances.suggested.toml" : fs::path(a.out);
  if (a.out.empty()) {
    const fs::path in_goldens =
        fs::weakly_canonical(out).lexically_relative(fs::weakly_canonical(suite.goldens));
    if (!in_goldens.empty() && *in_goldens.begin() != "..") {
      throw std::invalid_argument(hs::printable(out.string()) +
                                  ": inside the goldens folder; name another file with --out");
    }
  }
  write_text(out, hs::suggestions_toml(suite, all, reports, options));
  fmt::print(
      "suggested tolerances for {} of {} cases from {} runs: {} (review it; the suite is "
      "unchanged)\n",
      suggested, all.size(), reports.size(), hs::printable(out.string()));
  return suggested == all.size() ? kExitSame : kExitDifferent;
}

}  // namespace

void add_tolerances_command(CLI::App& app, int& rc) {
  CLI::App* cmd = app.add_subcommand("tolerances", "Work with a suite's tolerances");
  cmd->require_subcommand(1);
  CLI::App* suggest = cmd->add_subcommand(
      "suggest",
      "Propose each case's tolerance that passes every given run of the suite (reports of "
      "check), with the margin a run held back from the others needed, written into the last "
      "report folder for review. Exit status: 0 every case suggested, "
      "1 some not (listed, with why), 2 none or bad input (nothing written).");
  auto a = std::make_shared<SuggestArgs>();
  suggest
      ->add_option("suite", a->suite,
                   "suite file the reports are runs of; none for folder-mode reports (the "
                   "flags of one tolerance for every image are printed)")
      ->option_text("SUITE");
  suggest->add_option("--report", a->reports, "report folder of a check run (repeat, 2 or more)")
      ->required()
      ->option_text("DIR");
  suggest->add_option("--goldens", a->goldens, "goldens folder, if check was given --goldens")
      ->option_text("DIR");
  suggest
      ->add_option("--out", a->out,
                   "file to write (default: <last --report DIR>/tolerances.suggested.toml)")
      ->option_text("FILE");
  suggest
      ->add_option("--margin", a->margin,
                   "headroom in % of each measured value (default: per case, how far the "
                   "farthest run held back from the others fell from their limits; 0: the "
                   "tightest)")
      ->check(CLI::Range(0.0, 1000.0))
      ->option_text("PERCENT");
  guarded(suggest, rc, "tolerances suggest", [a] { return run_suggest(*a); });
}

}  // namespace aosuite::cli

#include "harness/suggest_toml.hpp"

#include <fmt/format.h>

#include "harness/escape.hpp"

namespace aosuite::harness {

namespace {

// One `key = value  # now <current>` line, the comment only where the suite says otherwise.
std::string line(std::string_view key, const std::string& value, const std::string& now) {
  return fmt::format("{} = {}{}\n", key, value, value == now ? "" : "  # now " + now);
}

std::string region_toml(const Region& r) {
  std::string out = fmt::format("{{ color = [{}, {}, {}]", r.color[0], r.color[1], r.color[2]);
  for (const metric::Gates& g : r.gates) out += ", " + gates_toml(g);
  return out + " }";
}

std::string case_toml(const Suggestion& s) {
  std::string out = fmt::format("\n[\"{}\"]  # from {} runs\n", s.id, s.runs.size());
  const Tolerance &now = s.current, &next = s.proposed;
  if (next.resemble) {
    out += fmt::format("mode = \"{}\"\n", resemble::mode_name(next.mode));
    out += line("max_mismatch_percent", fmt::format("{}", next.max_mismatch_percent),
                fmt::format("{}", now.max_mismatch_percent));
    const auto range = [](long long lo, long long hi) { return fmt::format("[{}, {}]", lo, hi); };
    if (now.min_channel_delta > 0) {  // written as the suite wrote it: two-sided
      out += line("channel_delta", range(next.min_channel_delta, next.max_channel_delta),
                  range(now.min_channel_delta, now.max_channel_delta));
    } else {
      out += line("max_channel_delta", fmt::format("{}", next.max_channel_delta),
                  fmt::format("{}", now.max_channel_delta));
    }
    out += line("max_mean_shift", fmt::format("{}", next.max_mean_shift),
                fmt::format("{}", now.max_mean_shift));
    out += line("max_mean_delta", fmt::format("{}", next.max_mean_delta),
                fmt::format("{}", now.max_mean_delta));
    if (now.max_differing_pixels >= 0) {
      out += line("differing_pixels", range(next.min_differing_pixels, next.max_differing_pixels),
                  range(now.min_differing_pixels, now.max_differing_pixels));
    }
  }
  for (std::size_t i = 0; i < next.gates.size(); ++i) {
    const std::string gates = gates_toml(next.gates[i]);
    const std::size_t eq = gates.find(" = ");
    out += line(gates.substr(0, eq), gates.substr(eq + 3), gates_toml(now.gates[i]).substr(eq + 3));
  }
  for (std::size_t i = 0; i < next.regions.size(); ++i) {
    out += line("regions." + next.regions[i].name, region_toml(next.regions[i]),
                region_toml(now.regions[i]));
  }
  for (const std::string& k : s.kept) out += "# " + k + "\n";
  return out;
}

}  // namespace

std::string gates_toml(const metric::Gates& g) {
  std::string out = std::string(g.metric->name) + " = {";
  const char* sep = " ";
  for (const metric::Limit& l : g.limits) {
    out += fmt::format("{}{}_{} = {}", sep, l.is_max ? "max" : "min", l.stat, l.limit);
    sep = ", ";
  }
  if (g.allow_nonfinite) out += std::string(sep) + "allow_nonfinite = true";
  return out + " }";
}

std::string suggestions_toml(const Suite& suite, const std::vector<Suggestion>& suggestions,
                             const std::vector<std::filesystem::path>& reports,
                             const SuggestOptions& options) {
  std::string out = fmt::format(
      "# Tolerances suggested by `aosuite tolerances suggest` for suite '{}' ({}), from {} "
      "runs:\n",
      suite.name, printable(suite.file.string()), reports.size());
  for (const std::filesystem::path& r : reports) out += "#   " + printable(r.string()) + "\n";
  out += fmt::format(
      "# Each table is the tightest tolerance that passes every run of its case: the largest\n"
      "# mismatch % and channel delta measured, each max_ gate's largest value and each min_\n"
      "# gate's smallest{}, rounded outward to 4 significant digits. Review it, then copy a\n"
      "# case's keys into its [case.tolerance]; ignore, mask and foreground_only stay as the\n"
      "# suite has them. aosuite never reads this file: the suite and its goldens are unchanged.\n",
      options.margin_percent > 0 ? fmt::format(", with a margin of {} %", options.margin_percent)
                                 : "");
  std::string skipped;
  for (const Suggestion& s : suggestions) {
    if (s.reason.empty()) {
      out += case_toml(s);
    } else {
      skipped += "#   " + s.id + ": " + s.reason + "\n";
    }
  }
  if (!skipped.empty()) out += "\n# Not suggested:\n" + skipped;
  return out;
}

}  // namespace aosuite::harness

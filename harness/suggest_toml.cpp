#include "harness/suggest_toml.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

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

// The keys of the tolerance that are not suggested, as the case has them now: the table
// replaces the case's whole [case.tolerance], so what it leaves out would fall back to the
// suite's [defaults.tolerance].
std::string kept_keys(const Suite& suite, const Tolerance& t) {
  std::string out;
  if (!t.resemble) out += "resemble = false\n";
  if (t.shift_radius != 0) out += fmt::format("shift_radius = {}\n", t.shift_radius);
  if (t.allow_kind_change) out += "allow_kind_change = true\n";
  if (t.foreground_only) out += "foreground_only = true\n";
  if (!t.ignore.empty()) {
    std::vector<std::string> boxes;
    for (const resemble::Box& b : t.ignore)
      boxes.push_back(fmt::format("[{}, {}, {}, {}]", b.left, b.top, b.right, b.bottom));
    out += fmt::format("ignore = [{}]\n", fmt::join(boxes, ", "));
  }
  if (!t.mask.empty()) {  // as the suite names it: relative to its folder
    const std::filesystem::path dir =
        suite.file.parent_path().empty() ? "." : suite.file.parent_path();
    out +=
        "mask = " + nlohmann::json(t.mask.lexically_relative(dir).generic_string()).dump() + "\n";
  }
  std::vector<std::string> floats;
  for (const metric::Gates& g : t.float_gates) floats.push_back(gates_toml(g));
  if (!floats.empty()) out += fmt::format("float = {{ {} }}\n", fmt::join(floats, ", "));
  const WarnLimits& w = t.warn;
  std::vector<std::string> warn;
  if (w.max_mismatch_percent < 100)
    warn.push_back(fmt::format("max_mismatch_percent = {}", w.max_mismatch_percent));
  if (w.max_channel_delta < 255)
    warn.push_back(fmt::format("max_channel_delta = {}", w.max_channel_delta));
  if (w.max_differing_pixels >= 0)
    warn.push_back(fmt::format("differing_pixels = {}", w.max_differing_pixels));
  for (const metric::Gates& g : w.gates) warn.push_back(gates_toml(g));
  if (!warn.empty()) out += fmt::format("warn = {{ {} }}\n", fmt::join(warn, ", "));
  return out;
}

// Why a case's limits are what they are: its runs and margin, then the margin's notes.
std::string why_toml(const Suggestion& s, std::string_view indent) {
  std::string out =
      fmt::format("#{} {}, from {} runs: {}\n", indent, s.id, s.runs.size(), margin_text(s));
  for (const std::string& n : s.margin_notes) out += fmt::format("#{}   {}\n", indent, n);
  return out;
}

// The [case.tolerance] table: `next`'s limits, each beside `now`'s where they differ, then the
// keys not suggested as the case has them, then the limits kept and why.
std::string tolerance_toml(const Suite& suite, const Tolerance& now, const Tolerance& next,
                           const std::vector<std::string>& kept) {
  std::string out = "[case.tolerance]\n";
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
  out += kept_keys(suite, now);
  for (const std::string& k : kept) out += "# " + k + "\n";
  return out;
}

// One [[case]]'s suggested ids (in suite order), one table: a [[case]] has one [case.tolerance]
// for every id it expands into, so several ids get the loosest of their suggestions (each max
// limit the largest, each min limit the smallest), which passes every run of each.
std::string table_toml(const Suite& suite, const std::vector<const Suggestion*>& ids) {
  if (ids.size() == 1) {
    const Suggestion& s = *ids.front();
    std::string out = "\n";  // appended, not `"\n" + ...`: GCC 12 misreads that (-Wrestrict)
    out += why_toml(s, "");
    return out + tolerance_toml(suite, s.current, s.proposed, s.kept);
  }
  std::vector<Suggestion> group;
  std::vector<std::string> names, kept;
  for (const Suggestion* s : ids) {
    group.push_back(*s);
    names.push_back(s->id);
    for (const std::string& k : s->kept)
      if (std::ranges::find(kept, k) == kept.end()) kept.push_back(k);
  }
  std::string out = fmt::format(
      "\n# {}: one [[case]], so one [case.tolerance], the loosest of their suggestions:\n",
      fmt::join(names, ", "));
  for (const Suggestion* s : ids) out += why_toml(*s, "  ");
  return out + tolerance_toml(suite, ids.front()->current, *loosest(group), kept);
}

}  // namespace

std::string margin_text(const Suggestion& s) {
  return fmt::format("+{} % on each limit, {}", s.margin_percent, s.margin_why);
}

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
      "# Each limit is the extreme its case's runs measured (the largest mismatch %, channel\n"
      "# delta, means and max_ gate values, the least min_ ones) widened by a margin, then\n"
      "# rounded outward to 4 significant digits. {}\n"
      "# Each [case.tolerance] is complete: after review, paste it over the one of the [[case]]\n"
      "# that makes the cases named above it (or below that [[case]]'s keys, if it has none).\n"
      "# aosuite never reads this file: the suite and its goldens are unchanged.\n",
      options.margin_percent
          ? fmt::format("The margin is {} % (--margin).", *options.margin_percent)
          : "The margin is chosen per case: each run was\n"
            "# held back in turn, and the farthest one fell from the limit the other runs set,\n"
            "# relative to it, widens every limit that varied between runs (none that never did).");
  // The suggested ids by the [[case]] that made them, in the suite's order.
  std::map<std::string, int> table_of;
  for (const Case& k : suite.cases) table_of[k.id] = k.table;
  std::map<int, std::vector<const Suggestion*>> tables;
  std::string skipped;
  for (const Suggestion& s : suggestions) {
    if (!s.reason.empty()) {
      skipped += "#   " + s.id + ": " + s.reason + "\n";
      continue;
    }
    tables[table_of.at(s.id)].push_back(&s);
  }
  for (const auto& [table, ids] : tables) out += table_toml(suite, ids);
  if (!skipped.empty()) out += "\n# Not suggested:\n" + skipped;
  return out;
}

}  // namespace aosuite::harness

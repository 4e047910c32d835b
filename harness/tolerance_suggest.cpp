#include "harness/tolerance_suggest.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "common/file_io.hpp"
#include "harness/escape.hpp"
#include "harness/results.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

namespace {

struct Run {
  fs::path dir;
  RunResults results;
  std::string name() const { return printable(dir.string()); }
};

// Each report, checked to be a run of `suite` against the goldens it has.
std::vector<Run> read_runs(const Suite& suite, const std::vector<fs::path>& reports) {
  std::vector<Run> runs;
  const std::string goldens = absolute_path(suite.goldens);
  for (const fs::path& dir : reports) {
    const std::string file = printable((dir / "results.json").string());
    Run run{dir, read_results(dir)};
    const RunResults& r = run.results;
    for (const Run& other : runs) {
      std::error_code ec;
      if (fs::equivalent(other.dir, dir, ec)) throw std::runtime_error(file + ": given twice");
    }
    const bool folders = !suite.expected.empty();
    if (folders != !r.expected_folder.empty()) {
      throw std::runtime_error(
          folders ? file + ": a run of suite '" + r.suite + "', not of folder mode"
                  : file + ": a folder-mode run, not a run of suite '" + suite.name + "'");
    }
    if (folders) {
      if (r.suite_file != absolute_path(suite.file) ||
          r.expected_folder != absolute_path(suite.expected)) {
        throw std::runtime_error(fmt::format("{}: compared {} with {}, not {} with {}", file,
                                             printable(r.suite_file), printable(r.expected_folder),
                                             printable(absolute_path(suite.file)),
                                             printable(absolute_path(suite.expected))));
      }
      runs.push_back(std::move(run));
      continue;
    }
    if (r.suite != suite.name) {
      throw std::runtime_error(
          fmt::format("{}: a run of suite '{}', not '{}'", file, r.suite, suite.name));
    }
    // Older results do not say; their goldens are checked image by image below.
    if (!r.goldens.empty() && r.goldens != goldens) {
      throw std::runtime_error(
          fmt::format("{}: judged the goldens in {}, not the suite's {} (--goldens names others)",
                      file, printable(r.goldens), printable(goldens)));
    }
    runs.push_back(std::move(run));
  }
  return runs;
}

// The file a run judged against, where the suite's goldens folder holds it now: its path below
// the case's folder (the image, or platform/image) under `goldens`.
fs::path golden_now(const fs::path& goldens, const std::string& id, const fs::path& judged) {
  fs::path tail = judged.filename(), dir = judged.parent_path();
  if (dir.filename() != id) tail = dir.filename() / tail;
  return goldens / id / tail;
}

// The judged golden still holds the bytes the run measured against.
bool golden_unchanged(const fs::path& file, const std::string& hash) {
  try {
    return golden_hash(read_regular_file(file)) == hash;
  } catch (const std::exception&) {
    return false;
  }
}

// What a run measured of one gated stat: its gate's outcome, else (for the whole image) the
// metric's own value; nothing when its tolerance then neither gated nor measured it.
std::optional<double> value_of(const ImageVerdict& v, std::string_view region,
                               const metric::Gates& g, const metric::Limit& l) {
  for (const metric::Outcome& o : v.outcomes) {
    if (o.region == region && o.metric == g.metric->name && o.stat == l.stat) return o.value;
  }
  for (const metric::Measurement& m : v.measured) {
    if (!region.empty() || m.metric != g.metric->name) continue;
    for (const metric::Value& value : m.values)
      if (value.key == l.stat) return value.value;
  }
  return std::nullopt;
}

// A limit the runs set: its name as the suite's keys say it, its side, whether it is a whole
// number, and whether the tolerance has it (a two-sided budget's lower end, Resemble's keys).
struct Stat {
  std::string name;
  bool is_max = true, whole = false, used = true;
};

// Resemble's stats, first in stats_of's order; the gates' limits follow from kGates on.
enum : std::size_t {
  kMismatch,
  kDelta,
  kLeastDelta,
  kMeanShift,
  kMeanDelta,
  kPixels,
  kLeastPixels,
  kGates
};

std::string limit_name(std::string_view region, const metric::Gates& g, const metric::Limit& l) {
  return fmt::format("{}{} {}_{}", region.empty() ? "" : std::string(region) + ": ", g.metric->name,
                     l.is_max ? "max" : "min", l.stat);
}

std::vector<Stat> stats_of(const Tolerance& t) {
  const bool r = t.resemble;
  std::vector<Stat> out = {{"max_mismatch_percent", true, false, r},
                           {"max_channel_delta", true, true, r},
                           {"channel_delta min", false, true, r && t.min_channel_delta > 0},
                           {"max_mean_shift", true, false, r},
                           {"max_mean_delta", true, false, r},
                           {"differing_pixels max", true, true, r && t.max_differing_pixels >= 0},
                           {"differing_pixels min", false, true, r && t.min_differing_pixels > 0}};
  for_each_limit(t, [&](std::string_view region, const metric::Gates& g, const metric::Limit& l) {
    out.push_back({limit_name(region, g, l), l.is_max});
  });
  return out;
}

// Per stat, the extreme over some images and runs (the largest for a max limit, the least for
// a min one): what its limit must let through; nothing where none measured it.
using Extremes = std::vector<std::optional<double>>;

void extend(std::optional<double>& extreme, double v, bool is_max) {
  extreme = !extreme ? v : is_max ? std::max(*extreme, v) : std::min(*extreme, v);
}

// The extremes over `runs`, leaving out the run `skip`.
Extremes merged(const std::vector<Stat>& stats, const std::vector<Extremes>& runs,
                std::size_t skip = std::size_t(-1)) {
  Extremes out(stats.size());
  for (std::size_t r = 0; r < runs.size(); ++r)
    for (std::size_t i = 0; i < stats.size(); ++i)
      if (r != skip && runs[r][i]) extend(out[i], *runs[r][i], stats[i].is_max);
  return out;
}

// The limit that lets `extreme` through, widened by `margin` % of it and rounded outward.
double limit_for(const Stat& s, double extreme, double margin) {
  double v = extreme + (s.is_max ? 1 : -1) * std::abs(extreme) * margin / 100;
  // A min limit never crosses 0 by its margin: a gate widened past 0 would hold nothing.
  if (!s.is_max && extreme > 0) v = std::max(v, 0.0);
  if (!s.whole) return round_outward(v, s.is_max);
  // A margin is a ratio of measured values: 6 widened by 1/6 is 7, not 7 plus a rounding error.
  const double snapped = std::abs(v - std::round(v)) < 1e-9 * std::abs(v) ? std::round(v) : v;
  return s.is_max ? std::ceil(snapped) : std::max(0.0, std::floor(snapped));
}

bool same_judging(const Tolerance& a, const Tolerance& b) {
  const auto box = [](const resemble::Box& x) {
    return std::array{x.left, x.top, x.right, x.bottom};
  };
  return a.mode == b.mode && a.foreground_only == b.foreground_only &&
         a.mask.empty() == b.mask.empty() && std::ranges::equal(a.ignore, b.ignore, {}, box, box);
}

// Adds an image's value of each gated stat to the extremes; returns the first it lacks
// ("edges: flip mean"), or "".
std::string observe_gates(const Tolerance& t, const ImageVerdict& v, const std::vector<Stat>& stats,
                          Extremes& seen) {
  std::size_t i = kGates;
  std::string missing;
  for_each_limit(t, [&](std::string_view region, const metric::Gates& g, const metric::Limit& l) {
    const std::optional<double> value = value_of(v, region, g, l);
    if (value) {
      extend(seen[i], *value, stats[i].is_max);
    } else if (missing.empty()) {
      missing = fmt::format("{}{} {}", region.empty() ? "" : std::string(region) + ": ",
                            g.metric->name, l.stat);
    }
    ++i;
  });
  return missing;
}

// One run's extremes of case `c` in `seen`; returns why they cannot be used, or "".
std::string observe(const Suite& suite, const Case& c, const Run& run, const CaseResult& r,
                    const std::vector<Stat>& stats, Extremes& seen) {
  const std::string at = run.name() + ": ";
  if (r.status == Status::kNew || r.status == Status::kError) {
    return at + std::string(status_name(r.status)) + " (" + printable(r.message) + ")";
  }
  if (r.status == Status::kFlaky) {
    return at + "FLAKY, and the failing attempt's numbers are not kept (check without --retries)";
  }
  if (!same_judging(r.tolerance, c.tolerance)) {
    return at +
           "judged under another mode, mask, ignored boxes or foreground than the suite's "
           "now (check again)";
  }
  for (const std::string& image : c.images) {
    const auto v = std::ranges::find(r.images, image, &ImageVerdict::image);
    if (v == r.images.end()) return at + "has no image '" + image + "' (check again)";
    if (v->golden_hash.empty()) return at + "made by an older aosuite (check again)";
    if (!v->comparable)
      return at + image + ": " + printable(v->message) + " (no tolerance passes it)";
    // Folder mode's golden is the expected folder's file (absolute: folder_suite_of).
    const fs::path now =
        suite.expected.empty() ? golden_now(suite.goldens, c.id, v->golden) : c.source->golden_file;
    if (!golden_unchanged(now, v->golden_hash)) {
      return at + image + ": the golden " + printable(now.string()) +
             " changed since (check again)";
    }
    for (const metric::Outcome& o : v->outcomes) {
      if (o.stat == "nonfinite" && !o.pass) return at + image + ": " + o.text();
    }
    if (!v->mismatch_text.empty()) {
      const double delta = v->max_channel_delta, pixels = double(v->differing_pixels);
      const std::pair<std::size_t, double> resemble[] = {{kMismatch, v->mismatch_percent},
                                                         {kDelta, delta},
                                                         {kLeastDelta, delta},
                                                         {kMeanShift, v->mean_shift},
                                                         {kMeanDelta, v->mean_delta},
                                                         {kPixels, pixels},
                                                         {kLeastPixels, pixels}};
      for (const auto& [i, value] : resemble) extend(seen[i], value, stats[i].is_max);
    }
    if (v->identical) continue;  // passes any limit: nothing measured
    if (const std::string lack = observe_gates(c.tolerance, *v, stats, seen); !lack.empty())
      return at + image + ": measured no " + lack + " (check again)";
  }
  return "";
}

// The default margin, in % per stat. Each run is held back in turn and the limits are set from
// the other runs (rounded outward, as always): how far the held-back run's value falls from
// that limit, relative to it, is how far a next run may fall from the runs seen. On either
// side: only the highest run ever lands above the others' limit, so that gap alone is one
// sample (on 31 seeds of the noisy runs in tests/tolerances_suggest_test.cpp, 18 of 186 later
// runs failed under it, 6 under the gap on either side). The case's margin is the farthest
// over its stats: its images share one source of noise, and one stat's few values (often
// tied, as whole numbers are) understate it. A stat that was the same in every run gets none.
std::vector<double> held_back_margins(const std::vector<Stat>& stats,
                                      const std::vector<Extremes>& runs, Suggestion& s) {
  std::vector<Extremes> others;
  for (std::size_t r = 0; r < runs.size(); ++r) others.push_back(merged(stats, runs, r));
  const Extremes all = merged(stats, runs);
  double widest = 0;
  std::vector<bool> varied(stats.size());
  std::vector<std::string> steady;
  for (std::size_t i = 0; i < stats.size(); ++i) {
    const Stat& st = stats[i];
    if (!st.used || !all[i] || !std::isfinite(*all[i])) continue;
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const std::optional<double> x = runs[r][i], rest = others[r][i];
      varied[i] = varied[i] || (x && *x != *all[i]);
      if (!x || !rest || !std::isfinite(*x) || !std::isfinite(*rest)) continue;
      const double limit = limit_for(st, *rest, 0);
      if (limit == 0) {  // no share of 0 reaches a value beyond it: the limit starts from it
        if (st.is_max ? *x <= 0 : *x >= 0) continue;
        s.margin_notes.push_back(fmt::format(
            "{}: {} in {}, where the other runs set 0, which no margin widens: the limit "
            "starts from {}",
            st.name, *x, s.runs[r], *x));
      } else if (const double w = 100 * std::abs(*x - limit) / std::abs(limit); w > widest) {
        widest = w;
        s.margin_why =
            fmt::format("the farthest a held-back run fell from the others' limit ({} in {})",
                        st.name, s.runs[r]);
      }
    }
    if (!varied[i]) steady.push_back(st.name);
  }
  s.margin_percent = round_outward(widest, true);
  if (widest == 0) s.margin_why = "no held-back run fell off the limits of the others";
  if (widest > 100)
    s.margin_notes.push_back(
        "over 100 %: the runs vary more than their values; more runs "
        "(or a look at why they differ) would give tighter limits");
  if (widest > 0 && !steady.empty())
    s.margin_notes.push_back(
        fmt::format("none on {}: the same in every run", fmt::join(steady, ", ")));
  std::vector<double> out(stats.size());
  for (std::size_t i = 0; i < stats.size(); ++i) out[i] = varied[i] ? widest : 0;
  return out;
}

// Sets `s.proposed` from the runs' extremes, each widened by its margin; `s.reason` when a
// limit cannot be met.
void propose(const std::vector<Stat>& stats, const std::vector<Extremes>& runs,
             const SuggestOptions& o, Suggestion& s) {
  std::vector<double> margin(stats.size(), o.margin_percent.value_or(0));
  if (o.margin_percent) {
    s.margin_percent = *o.margin_percent, s.margin_why = "--margin";
  } else {
    margin = held_back_margins(stats, runs, s);
  }
  const Extremes seen = merged(stats, runs);
  const auto limit = [&](std::size_t i) {
    return limit_for(stats[i], seen[i].value_or(0), margin[i]);
  };
  s.proposed = s.current;
  s.proposed.resemble = s.current.resemble && seen[kMismatch];
  s.proposed.max_mismatch_percent = std::min(100.0, limit(kMismatch));
  s.proposed.max_channel_delta = int(std::min(255.0, limit(kDelta)));
  s.proposed.max_mean_shift = limit(kMeanShift);
  s.proposed.max_mean_delta = limit(kMeanDelta);
  // A two-sided budget keeps its sides: the least seen, less the margin, at its lower end.
  if (stats[kLeastDelta].used) s.proposed.min_channel_delta = int(limit(kLeastDelta));
  if (stats[kPixels].used) s.proposed.max_differing_pixels = (long long)limit(kPixels);
  if (stats[kLeastPixels].used) s.proposed.min_differing_pixels = (long long)limit(kLeastPixels);
  std::size_t i = kGates;
  for_each_limit(s.proposed, [&](std::string_view, const metric::Gates&, metric::Limit& l) {
    const std::string& name = stats[i].name;
    if (!seen[i]) {
      s.kept.push_back(name + ": no run measured it (identical images); kept");
    } else if (std::isinf(*seen[i]) && !l.is_max) {
      s.kept.push_back(name +
                       ": +inf in every run (identical pixels), which any limit passes; kept");
    } else if (std::isinf(*seen[i])) {
      s.reason = name + ": +inf in a run (identical pixels), which no max_ limit passes";
    } else {
      l.limit = limit(i);
    }
    ++i;
  });
}

Suggestion suggest_case(const Suite& suite, const Case& c, const std::vector<Run>& runs,
                        const SuggestOptions& o) {
  Suggestion s;
  s.id = c.id, s.current = c.tolerance;
  const std::vector<Stat> stats = stats_of(c.tolerance);
  std::vector<Extremes> seen;  // per run
  for (const Run& run : runs) {
    const auto r = std::ranges::find(run.results.cases, c.id, &CaseResult::id);
    if (r == run.results.cases.end()) continue;
    s.runs.push_back(run.name());
    seen.emplace_back(stats.size());
    if (s.reason.empty()) s.reason = observe(suite, c, run, *r, stats, seen.back());
  }
  if (s.runs.size() < 2) {
    s.reason = s.runs.empty()
                   ? "in no report"
                   : "seen in one run (" + s.runs.front() + "); a suggestion needs two or more";
  }
  if (s.reason.empty()) propose(stats, seen, o, s);
  return s;
}

}  // namespace

double round_outward(double v, bool up) {
  if (v == 0 || !std::isfinite(v)) return v;
  const int exponent = 3 - int(std::floor(std::log10(std::abs(v))));
  // Powers of ten up to 1e22 are exact, so n / 10^k is the double nearest the decimal.
  const auto at = [&](double n) {
    return exponent >= 0 ? n / std::pow(10.0, exponent) : n * std::pow(10.0, -exponent);
  };
  const double scaled =
      exponent >= 0 ? v * std::pow(10.0, exponent) : v / std::pow(10.0, -exponent);
  double n = up ? std::ceil(scaled) : std::floor(scaled);
  // `scaled` is inexact: step to the multiple nearest `v` on its outer side.
  const double step = up ? 1 : -1;
  while (up ? at(n - step) >= v : at(n - step) <= v) n -= step;
  while (up ? at(n) < v : at(n) > v) n += step;
  return at(n);
}

std::vector<Suggestion> suggest(const Suite& suite, const std::vector<fs::path>& reports,
                                const SuggestOptions& options) {
  const std::vector<Run> runs = read_runs(suite, reports);
  std::vector<Suggestion> out;
  for (const Case& c : suite.cases) out.push_back(suggest_case(suite, c, runs, options));
  return out;
}

Suite folder_suite_of(const std::vector<fs::path>& reports) {
  std::vector<RunResults> runs;
  for (const fs::path& report : reports) runs.push_back(read_results(report));
  const RunResults& first = runs.front();
  if (first.expected_folder.empty()) {
    throw std::runtime_error(printable((reports.front() / "results.json").string()) +
                             ": a run of suite '" + first.suite + "'; name its suite file");
  }
  Suite suite = folder_suite(first.suite_file, first.expected_folder, Tolerance{});
  // Each image under the tolerance a run judged it by (a filtered run may have left it out).
  for (Case& c : suite.cases) {
    for (const RunResults& r : runs) {
      const auto judged = std::ranges::find(r.cases, c.id, &CaseResult::id);
      if (judged == r.cases.end()) continue;
      c.tolerance = judged->tolerance;
      break;
    }
  }
  return suite;
}

std::optional<Tolerance> loosest(const std::vector<Suggestion>& suggestions) {
  // A limit's identity, to match the same limit across images: region, metric, side, stat.
  const auto key = [](std::string_view region, const metric::Gates& g, const metric::Limit& l) {
    return fmt::format("{}/{}/{}_{}", region, g.metric->name, l.is_max ? "max" : "min", l.stat);
  };
  std::optional<Tolerance> out;
  for (const Suggestion& s : suggestions) {
    if (!s.reason.empty()) continue;
    if (!out) {
      out = s.proposed;
      continue;
    }
    out->resemble = out->resemble || s.proposed.resemble;
    out->max_mismatch_percent =
        std::max(out->max_mismatch_percent, s.proposed.max_mismatch_percent);
    out->max_channel_delta = std::max(out->max_channel_delta, s.proposed.max_channel_delta);
    out->max_mean_shift = std::max(out->max_mean_shift, s.proposed.max_mean_shift);
    out->max_mean_delta = std::max(out->max_mean_delta, s.proposed.max_mean_delta);
    std::map<std::string, double> limits;
    for_each_limit(s.proposed,
                   [&](std::string_view region, const metric::Gates& g, const metric::Limit& l) {
                     limits[key(region, g, l)] = l.limit;
                   });
    for_each_limit(*out, [&](std::string_view region, const metric::Gates& g, metric::Limit& l) {
      const auto it = limits.find(key(region, g, l));
      if (it != limits.end())
        l.limit = l.is_max ? std::max(l.limit, it->second) : std::min(l.limit, it->second);
    });
  }
  return out;
}

std::string folder_flags(const Tolerance& t) {
  std::string out;
  if (t.resemble) {
    out = fmt::format(
        "--max-mismatch {} --max-channel-delta {} --limit max_mean_shift={} "
        "--limit max_mean_delta={}",
        t.max_mismatch_percent, t.max_channel_delta, t.max_mean_shift, t.max_mean_delta);
  }
  for (const metric::Gates& g : t.gates) {
    for (const metric::Limit& l : g.limits) {
      out += fmt::format("{}--gate {}.{}_{}={}", out.empty() ? "" : " ", g.metric->name,
                         l.is_max ? "max" : "min", l.stat, l.limit);
    }
  }
  return out;
}

}  // namespace aosuite::harness

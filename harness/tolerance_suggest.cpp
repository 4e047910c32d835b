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

// The extremes over every run: what the limits must let through.
struct Observed {
  bool resemble = false;  // some image had Resemble's numbers
  double mismatch = 0;
  int delta = 0, least_delta = 255;  // the two-sided budgets' ends
  double mean_shift = 0, mean_delta = 0;
  long long pixels = 0, least_pixels = -1;
  std::vector<std::optional<double>> limits;  // per limit, in for_each_limit's order
};

bool same_judging(const Tolerance& a, const Tolerance& b) {
  const auto box = [](const resemble::Box& x) {
    return std::array{x.left, x.top, x.right, x.bottom};
  };
  return a.mode == b.mode && a.foreground_only == b.foreground_only &&
         a.mask.empty() == b.mask.empty() && std::ranges::equal(a.ignore, b.ignore, {}, box, box);
}

// Adds an image's value of each gated stat to the extremes; returns the first it lacks
// ("edges: flip mean"), or "".
std::string observe_gates(const Tolerance& t, const ImageVerdict& v, Observed& seen) {
  std::size_t i = 0;
  std::string missing;
  for_each_limit(t, [&](std::string_view region, const metric::Gates& g, const metric::Limit& l) {
    std::optional<double>& extreme = seen.limits[i++];
    const std::optional<double> value = value_of(v, region, g, l);
    if (!value) {
      if (missing.empty())
        missing = fmt::format("{}{} {}", region.empty() ? "" : std::string(region) + ": ",
                              g.metric->name, l.stat);
    } else {
      extreme = !extreme   ? *value
                : l.is_max ? std::max(*extreme, *value)
                           : std::min(*extreme, *value);
    }
  });
  return missing;
}

// Adds one run's numbers for case `c`; returns why they cannot be used, or "".
std::string observe(const Suite& suite, const Case& c, const Run& run, const CaseResult& r,
                    Observed& seen) {
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
      seen.resemble = true;
      seen.mismatch = std::max(seen.mismatch, v->mismatch_percent);
      seen.delta = std::max(seen.delta, v->max_channel_delta);
      seen.mean_shift = std::max(seen.mean_shift, v->mean_shift);
      seen.mean_delta = std::max(seen.mean_delta, v->mean_delta);
      seen.least_delta = std::min(seen.least_delta, v->max_channel_delta);
      seen.pixels = std::max(seen.pixels, v->differing_pixels);
      seen.least_pixels = seen.least_pixels < 0 ? v->differing_pixels
                                                : std::min(seen.least_pixels, v->differing_pixels);
    }
    if (v->identical) continue;  // passes any limit: nothing measured
    if (const std::string lack = observe_gates(c.tolerance, *v, seen); !lack.empty())
      return at + image + ": measured no " + lack + " (check again)";
  }
  return "";
}

// Sets `s.proposed` from the extremes; `s.reason` when a limit cannot be met.
void propose(const Observed& seen, const SuggestOptions& o, Suggestion& s) {
  const double up = 1 + o.margin_percent / 100;
  s.proposed = s.current;
  s.proposed.resemble = s.current.resemble && seen.resemble;
  s.proposed.max_mismatch_percent = std::min(100.0, round_outward(seen.mismatch * up, true));
  s.proposed.max_channel_delta = std::min(255, int(std::ceil(seen.delta * up)));
  // The means as the other limits: the largest any run measured, with the margin.
  s.proposed.max_mean_shift = round_outward(seen.mean_shift * up, true);
  s.proposed.max_mean_delta = round_outward(seen.mean_delta * up, true);
  // A two-sided budget keeps its sides: the least seen (less the margin) at its lower end.
  if (s.current.min_channel_delta > 0)
    s.proposed.min_channel_delta = int(std::floor(seen.least_delta / up));
  if (s.current.max_differing_pixels >= 0)
    s.proposed.max_differing_pixels = (long long)std::ceil(double(seen.pixels) * up);
  if (s.current.min_differing_pixels > 0)
    s.proposed.min_differing_pixels = (long long)std::floor(double(seen.least_pixels) / up);
  std::size_t i = 0;
  for_each_limit(
      s.proposed, [&](std::string_view region, const metric::Gates& g, metric::Limit& l) {
        const std::optional<double>& extreme = seen.limits[i++];
        const std::string name =
            fmt::format("{}{} {}_{}", region.empty() ? "" : std::string(region) + ": ",
                        g.metric->name, l.is_max ? "max" : "min", l.stat);
        if (!extreme) {
          s.kept.push_back(name + ": no run measured it (identical images); kept");
        } else if (std::isinf(*extreme) && !l.is_max) {
          s.kept.push_back(name +
                           ": +inf in every run (identical pixels), which any limit passes; kept");
        } else if (std::isinf(*extreme)) {
          s.reason = name + ": +inf in a run (identical pixels), which no max_ limit passes";
        } else {
          const double headroom = std::abs(*extreme) * o.margin_percent / 100;
          l.limit = round_outward(l.is_max ? *extreme + headroom : *extreme - headroom, l.is_max);
        }
      });
}

Suggestion suggest_case(const Suite& suite, const Case& c, const std::vector<Run>& runs,
                        const SuggestOptions& o) {
  Suggestion s;
  s.id = c.id, s.current = c.tolerance;
  Observed seen;
  for_each_limit(c.tolerance, [&](auto, auto&, auto&) { seen.limits.emplace_back(); });
  for (const Run& run : runs) {
    const auto r = std::ranges::find(run.results.cases, c.id, &CaseResult::id);
    if (r == run.results.cases.end()) continue;
    s.runs.push_back(run.name());
    if (s.reason.empty()) s.reason = observe(suite, c, run, *r, seen);
  }
  if (s.runs.size() < 2) {
    s.reason = s.runs.empty()
                   ? "in no report"
                   : "seen in one run (" + s.runs.front() + "); a suggestion needs two or more";
  }
  if (s.reason.empty()) propose(seen, o, s);
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

#include "harness/html_report.hpp"

#include <fmt/format.h>
#include <xxhash.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string_view>

#include "common/file_io.hpp"
#include "harness/case_kind.hpp"
#include "harness/escape.hpp"
#include "harness/report_images.hpp"
#include "harness/runner.hpp"

namespace aosuite::harness {

const std::map<std::string_view, std::string_view>& report_assets();  // generated

namespace {

namespace fs = std::filesystem;

std::string base64(std::span<const unsigned char> in) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < in.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, in.size() - i);
    std::uint32_t v = static_cast<std::uint32_t>(in[i]) << 16;
    if (n > 1) v |= static_cast<std::uint32_t>(in[i + 1]) << 8;
    if (n > 2) v |= in[i + 2];
    for (std::size_t k = 0; k < 4; ++k) {
      out += k <= n ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
    }
  }
  return out;
}

// Collects the pictures, each stored once under its content hash.
class Pictures {
 public:
  explicit Pictures(fs::path cases_dir) : dir_(std::move(cases_dir)) {}
  // The key of `rel`'s bytes in the table, adding them; empty when it is not a plain file
  // inside cases/.
  std::string key(const std::string& rel) {
    if (!inside(dir_, rel)) return "";
    const std::vector<unsigned char> bytes = read_file(dir_ / rel);
    const std::string key = fmt::format("{:016x}", XXH3_64bits(bytes.data(), bytes.size()));
    if (!data_.contains(key)) data_[key] = base64(bytes);
    return key;
  }
  std::string json() const {
    std::string out = "{";
    for (const auto& [key, b64] : data_)
      out += fmt::format("{}\"{}\":\"{}\"", out.size() > 1 ? "," : "", key, b64);
    return out + "}";
  }

 private:
  fs::path dir_;
  std::map<std::string, std::string> data_;
};

std::string file_of(const CaseResult& c, const std::string& role) {
  const auto it = c.files.find(role);
  return it == c.files.end() ? std::string() : it->second;
}

// A metric gate as the page names it ("edges: flip mean") and its limit ("≤ 0.02").
std::string gate_name(const metric::Outcome& o) {
  return (o.region.empty() ? "" : o.region + ": ") + o.metric + " " + o.stat;
}
std::string limit_text(const metric::Outcome& o) {
  return o.stat == "nonfinite" ? "0" : fmt::format("{}{:.6g}", o.is_max ? "≤ " : "≥ ", o.limit);
}

// The gate a case came nearest to failing, in that gate's own units: Resemble's mismatch in
// percent (margin in percentage points), or a metric gate's value, limit and margin. `score`
// ranks cases across kinds of gate: Resemble's margin, or a metric's as a percentage of its
// limit (negative = over); NaN when nothing was measured.
struct Nearest {
  double score = std::nan("");
  std::string value, limit, margin;
};

Nearest nearest_gate(const CaseResult& c) {
  Nearest n;
  double worst = HUGE_VAL;
  for (const ImageVerdict& v : c.images) {
    if (v.status != Status::kPass && v.status != Status::kFail && v.status != Status::kWarn)
      continue;
    // Which image, when the case has several.
    const std::string of = c.images.size() > 1 ? v.image + ": " : "";
    if (c.tolerance.resemble) {
      const double m = c.tolerance.max_mismatch_percent - v.mismatch_percent;
      if (m < worst) {
        worst = m;
        n = {m, fmt::format("{}{}%", of, v.mismatch_text),
             fmt::format("≤ {}%", c.tolerance.max_mismatch_percent), fmt::format("{:+.4f}", m)};
      }
    }
    for (const metric::Outcome& o : v.outcomes) {
      const double m = o.limit != 0 ? 100 * o.margin / std::abs(o.limit) : o.margin;
      if (m < worst) {
        worst = m;
        n = {m, fmt::format("{}{} {:.6g}", of, gate_name(o), o.value), limit_text(o),
             fmt::format("{:+.6g}", o.margin)};
      }
    }
  }
  return n;
}

// The tolerance in words: Resemble's gate when it holds, then each metric gate.
std::string tolerance_text(const Tolerance& t) {
  std::string out;
  if (t.resemble) {
    out = fmt::format("mode {}, ≤ {}% mismatch, channel Δ ≤ {}", resemble::mode_name(t.mode),
                      t.max_mismatch_percent, t.max_channel_delta);
  }
  for (const metric::Gates& g : t.gates) {
    for (const metric::Limit& l : g.limits) {
      out += fmt::format("{}{} {} {} {}", out.empty() ? "" : "; ", g.metric->name, l.stat,
                         l.is_max ? "≤" : "≥", l.limit);
    }
    if (g.allow_nonfinite) out += fmt::format(" ({} allows NaN/Inf)", g.metric->name);
  }
  for (const Region& r : t.regions) {
    for (const metric::Gates& g : r.gates) {
      for (const metric::Limit& l : g.limits) {
        out += fmt::format("; region {} ({},{},{}): {} {} {} {}", r.name, r.color[0], r.color[1],
                           r.color[2], g.metric->name, l.stat, l.is_max ? "≤" : "≥", l.limit);
      }
    }
  }
  if (t.foreground_only) out += "; over geometry pixels only";
  return out;
}

nlohmann::json gates_json(const ImageVerdict& v) {
  nlohmann::json out = nlohmann::json::array();
  for (const metric::Outcome& o : v.outcomes) {
    out.push_back({{"gate", gate_name(o)},
                   {"value", fmt::format("{:.6g}", o.value)},
                   {"limit", limit_text(o)},
                   {"margin", fmt::format("{:+.6g}", o.margin)},
                   {"pass", o.pass}});
  }
  return out;
}

}  // namespace

void write_html_report(const RunResults& run, const fs::path& report_dir,
                       const ReportOptions& options) {
  const fs::path cases_dir = report_dir / "cases";
  Pictures pics(cases_dir);
  // Each picture as the page loads it: a file beside index.html, or (single file) a key into
  // the embedded table.
  auto url = [&](const std::string& rel) -> std::string {
    if (rel.empty()) return "";
    if (options.single_file) {
      const std::string key = pics.key(rel);
      return key.empty() ? "" : "k:" + key;
    }
    return inside(cases_dir, rel) ? "cases/" + rel : "";
  };

  // Failures and NEW first, then flaky, warnings, then passes by margin: near misses before easy
  // passes.
  std::vector<std::size_t> order(run.cases.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::vector<Nearest> nearest(run.cases.size());
  for (std::size_t i = 0; i < run.cases.size(); ++i) nearest[i] = nearest_gate(run.cases[i]);
  const auto margin = [&](std::size_t i) {
    return std::isnan(nearest[i].score) ? 1e300 : nearest[i].score;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const int sa = severity(run.cases[a].status), sb = severity(run.cases[b].status);
    return sa != sb ? sa > sb : margin(a) < margin(b);
  });
  // What the page shows of an image: itself, or its preview when a browser cannot show it
  // (made once per file, however many roles name it).
  std::map<std::string, std::string> previews;
  const auto shown = [&](const std::string& rel) {
    const auto [it, added] = previews.try_emplace(rel);
    if (added) it->second = shown_image(cases_dir, rel);
    return it->second;
  };
  // The golden or new image of a verdict under `role`, and under `role`_file the file itself
  // when what is shown is its preview: the page links it beside the picture.
  const auto picture = [&](nlohmann::json& into, const std::string& role, const std::string& rel) {
    const std::string show = shown(rel);
    into[role] = url(show);
    into[role + "_file"] = show != rel && inside(cases_dir, rel) ? "cases/" + rel : "";
    into[role + "_stops"] = show != rel ? stops_of_preview(show) : 0;
  };

  // The table's rows are drawn by the page from this, a screenful at a time: a report of
  // thousands of cases parses and lays out no more rows than are looked at.
  nlohmann::json data = nlohmann::json::array();
  for (std::size_t n = 0; n < order.size(); ++n) {
    const CaseResult& c = run.cases[order[n]];
    std::string delta;
    nlohmann::json images = nlohmann::json::array();
    for (const ImageVerdict& v : c.images) {
      delta += (delta.empty() ? "" : " / ") +
               (v.largest.x < 0 ? std::to_string(v.max_channel_delta) : v.largest.text());
      nlohmann::json image = {{"image", v.image},
                              {"status", status_name(v.status)},
                              {"mismatch", v.mismatch_text},
                              {"delta", v.max_channel_delta},
                              {"largest", v.largest.text()},
                              {"changes", printable(comparison::changes_text(v.changes, 5))},
                              {"identical", v.identical},
                              {"message", printable(v.message)},
                              {"diff", url(file_of(c, "diff:" + v.image))},
                              {"heat", url(file_of(c, "heat:" + v.image))},
                              {"abs", url(file_of(c, "abs:" + v.image))},
                              {"signed", url(file_of(c, "signed:" + v.image))},
                              {"regions", url(file_of(c, "regions:" + v.image))},
                              {"ignored", url(file_of(c, "ignored:" + v.image))},
                              {"gates", gates_json(v)},
                              {"golden_path", printable(v.golden.string())}};
      picture(image, "new", file_of(c, v.image));
      picture(image, "golden", file_of(c, "golden:" + v.image));
      images.push_back(std::move(image));
    }
    // The thumbnail: the first gated image (the golden where there is no new one).
    std::string thumb;
    nlohmann::json thumb_stops;  // a float image's: its preview's stops, for the exposure filter
    if (!c.images.empty()) {
      const std::string& first = c.images.front().image;
      std::string rel = file_of(c, first);
      if (rel.empty() || !inside(cases_dir, rel)) rel = file_of(c, "golden:" + first);
      const std::string show = shown(rel);
      thumb = url(thumbnail(cases_dir, show));
      if (show != rel) thumb_stops = stops_of_preview(show);
    }
    // Each failing attempt of a retried case: its verdict and the pictures it left.
    nlohmann::json attempts = nlohmann::json::array();
    for (const Attempt& a : c.failed_attempts) {
      // Its images by name, from its own files (the last attempt may have judged none).
      std::set<std::string> names;
      for (const auto& [role, rel] : a.files) names.insert(role.substr(role.find(':') + 1));
      const auto file = [&](const std::string& role) {
        const auto it = a.files.find(role);
        return it == a.files.end() ? std::string() : it->second;
      };
      nlohmann::json pictures = nlohmann::json::array();
      for (const std::string& name : names) {
        nlohmann::json p = {{"image", name}, {"diff", url(file("diff:" + name))}};
        picture(p, "new", file(name));
        picture(p, "golden", file("golden:" + name));
        pictures.push_back(std::move(p));
      }
      attempts.push_back({{"status", status_name(a.status)},
                          {"message", printable(a.message)},
                          {"images", pictures}});
    }
    nlohmann::json about = nlohmann::json::object();
    for (const auto& [label, value] : c.labels) about[printable(label)] = printable(value);
    if (c.width > 0) about["size"] = fmt::format("{}x{}", c.width, c.height);
    about["tolerance"] = tolerance_text(c.tolerance);
    nlohmann::json params = nlohmann::json::object();
    for (const auto& [k, v] : c.params)
      params[k] = v.is_string() ? printable(v.get<std::string>()) : v.dump();
    nlohmann::json times = nlohmann::json::object();
    for (const Timing& t : c.times) times[printable(t.stage)] = fmt::format("{:.3f} ms", t.ms);
    data.push_back({{"id", c.id},
                    {"status", status_name(c.status)},
                    {"kind", c.kind},
                    {"source", printable(c.source)},
                    {"message", printable(c.message)},
                    {"not_reused", printable(c.not_reused)},
                    {"bless", printable(c.bless_command)},
                    {"exit", c.exit_status},
                    {"stderr", printable_lines(c.command_stderr)},
                    {"attempts", c.attempts},
                    {"images_left_out", c.images_left_out},
                    {"failed_attempts", attempts},
                    {"measured", nearest[order[n]].value},
                    {"limit", nearest[order[n]].limit},
                    {"margin", nearest[order[n]].margin},
                    {"delta", delta},
                    {"seconds", std::round(c.seconds * 100) / 100},
                    {"thumb", thumb},
                    {"thumb_stops", thumb_stops},
                    {"allowed", c.tolerance.max_mismatch_percent},
                    {"resemble", c.tolerance.resemble},
                    {"about", about},
                    {"params", params},
                    {"times", times},
                    {"images", images}});
  }

  const Counts n = count(run);
  const std::string approve_failed =
      run.approve_prefix.empty()
          ? std::string()
          : accept_report_command(run.bless_prefix, report_dir.lexically_normal());
  const nlohmann::json meta = {{"approve", printable(run.approve_prefix)},
                               {"approve_failed", printable(approve_failed)}};
  std::string body = fmt::format(
      "<header><h1>aosuite: {}</h1>\n<p>{} cases: <span class=PASS>{} passed</span>, <span "
      "class=FAIL>{} failed</span>, <span class=NEW>{} new</span>, <span class=ERROR>{} "
      "errors</span>{}{}. Suite <code>{}</code>{}.{}</p>\n",
      escape_markup(run.suite), run.cases.size(), n.pass, n.fail, n.fresh, n.error,
      n.flaky ? fmt::format(", <span class=FLAKY>{} flaky</span>", n.flaky) : "",
      n.warn ? fmt::format(", <span class=WARN>{} with warnings</span>", n.warn) : "",
      escape_markup(run.suite_file), run.shard.empty() ? "" : ", shard " + escape_markup(run.shard),
      run.environment.empty() ? ""
                              : " Made on " + escape_markup(run.environment) + " (platform <code>" +
                                    escape_markup(run.platform) + "</code>).");
  // Two views of the same cases: the table (one case opened beside it), and every FAIL, NEW,
  // WARN and ERROR case on one scrolling page.
  body += fmt::format(
      "<nav id=bar><span id=views><button data-view=table class=on>table</button> <button "
      "data-view=failures>failures on one page (<span id=failing>{}</span>)</button></span> "
      "<span id=filters>",
      n.fail + n.fresh + n.error + n.warn);
  for (const char* st : {"ERROR", "FAIL", "NEW", "FLAKY", "WARN", "PASS"}) {
    int count_of = 0;
    for (const CaseResult& c : run.cases) count_of += status_name(c.status) == st;
    body += fmt::format(
        R"(<label class={0}><input type=checkbox data-status={0} checked> {0} ({1})</label> )", st,
        count_of);
  }
  // The approve bar stays at the top of the window however far either view is scrolled.
  body +=
      "</span><input id=search type=search placeholder=\"filter: id, path, message (/)\" "
      "aria-label=filter> <span id=shown></span></nav>\n"
      "<p class=keys>Keys: j/k or ↓/↑ move, n/p next/previous failure, Enter open, Esc close, "
      "x select, / filter, v switch view; in a case: f fit, 1 one-to-one, +/− zoom, m largest "
      "difference, b flicker golden/new; drag a zoomed view to pan them all, the panel's edge to "
      "resize it.</p>"
      "</header>\n<div id=approve><button id=select-failing>select shown FAIL/NEW</button> "
      "<button id=select-none>clear</button> <span id=selected>0 selected</span>: <code "
      "id=command></code> <button id=copy>copy</button> <span id=copied></span></div>\n";
  body +=
      "<main><div id=table-view><table id=cases><thead><tr><th></th><th>status</th><th>case</th>"
      "<th class=wide>measured</th><th class=wide>limit</th><th>margin</th><th>max Δ</th>"
      "<th class=wide>time s</th><th>image</th>"
      "</tr></thead><tbody></tbody></table>\n<p id=more></p><noscript>This report needs "
      "JavaScript; results.json holds the same.</noscript>\n";
  // Each registered kind with cases here adds its own section (the AO bench: its tables).
  std::set<std::string> kinds;
  for (const CaseResult& c : run.cases)
    if (!is_image_kind(c.kind)) kinds.insert(c.kind);
  for (const std::string& name : kinds)
    if (const CaseKind* kind = find_kind(name)) body += kind->report_section(run, report_dir);
  body +=
      "</div><div id=failures-view hidden><div id=failures></div><p id=failures-more></p></div>"
      "</main><aside id=detail hidden></aside>\n";
  const std::string page = fmt::format(
      "<!doctype html>\n<html lang=en><head><meta charset=utf-8><title>aosuite: {}</title>"
      "<style>{}</style></head><body>\n{}<script type=\"application/json\" id=meta>{}</script>"
      "<script type=\"application/json\" id=data>{}</script>"
      "<script type=\"application/json\" id=images>{}</script>"
      "<script>{}</script></body></html>\n",
      escape_markup(run.suite), report_assets().at("report.css"), body, json_in_script(meta),
      json_in_script(data), options.single_file ? pics.json() : "{}",
      report_assets().at("report.js"));
  fs::create_directories(report_dir);
  write_report_file(report_dir / "index.html",
                    {reinterpret_cast<const unsigned char*>(page.data()), page.size()});
}

std::string report_size(const fs::path& dir) {
  std::uintmax_t bytes = 0, files = 0;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file(ec) && !it->is_symlink(ec)) bytes += it->file_size(ec), ++files;
  }
  return fmt::format("{} file{}, {:.1f} MB", files, files == 1 ? "" : "s", double(bytes) / 1e6);
}

}  // namespace aosuite::harness

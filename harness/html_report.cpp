#include "harness/html_report.hpp"

#include <fmt/format.h>
#include <xxhash.h>

#include <chrono>
#include <map>
#include <string_view>

#include "compare/image_io.hpp"
#include "harness/escape.hpp"

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
  // An <img> showing `rel` (relative to cases/), or a note when the file is missing.
  std::string img(const std::string& rel, std::string_view cls, std::string_view alt) {
    // Only a plain file inside cases/: a report never embeds anything else on the machine.
    const fs::path file = dir_ / rel;
    std::error_code ec;
    const fs::path r = fs::path(rel).lexically_normal();
    const bool inside = !rel.empty() && r.is_relative() && !r.empty() && *r.begin() != "..";
    if (!inside || !fs::is_regular_file(fs::symlink_status(file, ec))) {
      return "<p><em>(no image)</em></p>";
    }
    const std::vector<unsigned char> bytes = read_file(file);
    const std::string key = fmt::format("{:016x}", XXH3_64bits(bytes.data(), bytes.size()));
    if (!data_.contains(key)) data_[key] = base64(bytes);
    return fmt::format(R"(<img class="{}" data-key="{}" alt="{}">)", cls, key, escape_markup(alt));
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

// escape_markup() line by line, keeping the line breaks (for <pre>).
std::string escape_lines(std::string_view text) {
  std::string out;
  for (std::size_t at = 0; at <= text.size();) {
    const std::size_t nl = std::min(text.find('\n', at), text.size());
    out += escape_markup(text.substr(at, nl - at));
    if (nl < text.size()) out += '\n';
    at = nl + 1;
  }
  return out;
}

std::string status_cell(Status s) {
  return fmt::format(R"(<span class="{0}">{0}</span>)", status_name(s));
}

// How close a case came to its limit: allowed minus measured mismatch (negative = over).
std::string margin(const CaseResult& c) {
  double worst = c.tolerance.max_mismatch_percent;
  bool any = false;
  for (const ImageVerdict& v : c.images) {
    if (v.status == Status::kPass || v.status == Status::kFail) {
      worst = std::min(worst, c.tolerance.max_mismatch_percent - v.mismatch_percent);
      any = true;
    }
  }
  return any ? fmt::format("{:+.4f}", worst) : "";
}

std::string summary_table(const RunResults& run) {
  std::string h =
      "<table><tr><th>case</th><th>status</th><th>mismatch %</th><th>allowed %</th>"
      "<th>margin</th><th>max Δ</th><th>time s</th><th>reused</th></tr>\n";
  for (const CaseResult& c : run.cases) {
    std::string mismatch, delta;
    for (const ImageVerdict& v : c.images) {
      mismatch += (mismatch.empty() ? "" : " / ") + escape_markup(v.image + " " + v.mismatch_text);
      delta += (delta.empty() ? "" : " / ") + std::to_string(v.max_channel_delta);
    }
    h += fmt::format(
        "<tr><td><a href=\"#{0}\">{0}</a></td><td>{1}</td><td>{2}</td><td class=num>{3}</td>"
        "<td class=num>{4}</td><td class=num>{5}</td><td class=num>{6:.2f}</td><td>{7}</td></tr>\n",
        escape_markup(c.id), status_cell(c.status), mismatch, c.tolerance.max_mismatch_percent,
        margin(c), delta, c.seconds, c.reused ? "yes" : "");
  }
  return h + "</table>\n";
}

// The thesis's Tables 11-14: per technique, how much of the image AO changes.
std::string ao_effect_table(const RunResults& run) {
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> by;
  for (const CaseResult& c : run.cases) {
    if (c.status == Status::kError) continue;
    by[c.technique].first.push_back(c.ao_effect_less);
    by[c.technique].second.push_back(c.ao_effect_nothing);
  }
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0 : s / static_cast<double>(v.size());
  };
  std::string h =
      "<table><tr><th>technique</th><th>cases</th><th>ignoreLess mismatch %</th>"
      "<th>ignoreNothing mismatch %</th></tr>\n";
  for (const auto& [t, v] : by) {
    h += fmt::format(
        "<tr><td>{}</td><td class=num>{}</td><td class=num>{:.2f}</td>"
        "<td class=num>{:.2f}</td></tr>\n",
        escape_markup(t), v.first.size(), mean(v.first), mean(v.second));
  }
  return h + "</table>\n";
}

std::string kv_table(const std::map<std::string, std::string>& kv) {
  std::string h = "<table>";
  for (const auto& [k, v] : kv) {
    h += fmt::format("<tr><th>{}</th><td>{}</td></tr>", escape_markup(k), escape_markup(v));
  }
  return h + "</table>";
}

std::string figure(const std::string& img, std::string_view caption) {
  return fmt::format("<figure>{}<figcaption>{}</figcaption></figure>", img, caption);
}

std::string image_comparison(const CaseResult& c, const ImageVerdict& v, Pictures& pics) {
  const std::string fresh = file_of(c, v.image), golden = file_of(c, "golden:" + v.image);
  std::string h = fmt::format("<h4>{} — {} {}% (allowed {}%), max channel Δ {}{}</h4>\n",
                              escape_markup(v.image), status_cell(v.status),
                              escape_markup(v.mismatch_text), c.tolerance.max_mismatch_percent,
                              v.max_channel_delta, v.identical ? ", byte-identical" : "");
  if (!v.message.empty()) h += "<p>" + escape_markup(v.message) + "</p>\n";
  h += "<div class=images>";
  if (!golden.empty()) h += figure(pics.img(golden, "", "golden"), "golden");
  h += figure(pics.img(fresh, "", "new"), "new");
  if (const std::string diff = file_of(c, "diff:" + v.image); !diff.empty()) {
    h += figure(pics.img(diff, "", "diff"), "diff");
  }
  if (!golden.empty() && !v.identical) {
    h += figure("<div class=swap>" + pics.img(golden, "golden", "golden") +
                    pics.img(fresh, "new", "new") + "</div>",
                "golden; hover for new");
    h += figure("<div class=slider>" + pics.img(golden, "", "golden") +
                    pics.img(fresh, "top", "new") +
                    "<input type=range min=0 max=100 value=50 aria-label=\"new vs golden\"></div>",
                "slider: new (left) over golden");
  }
  return h + "</div>\n";
}

std::string case_section(const CaseResult& c, Pictures& pics) {
  std::string h = fmt::format("<section class=case id=\"{0}\"><h2>{0} {1}</h2>\n",
                              escape_markup(c.id), status_cell(c.status));
  if (!c.message.empty()) h += "<p>" + escape_markup(c.message) + "</p>\n";
  if (!c.bless_command.empty()) {
    h += "<p>Accept this render as the golden: <code>" + escape_markup(c.bless_command) +
         "</code></p>\n";
  }
  if (c.exit_status >= 0 || !c.source.empty()) {
    h += fmt::format("<p>{} <code>{}</code>{}</p>\n", c.kind == "command" ? "Command" : "Source",
                     escape_markup(c.source),
                     c.exit_status >= 0 ? fmt::format(", exit status {}", c.exit_status) : "");
  }
  if (!c.command_stderr.empty()) {
    h += "<details><summary>stderr</summary><pre>" + escape_lines(c.command_stderr) +
         "</pre></details>\n";
  }
  for (const ImageVerdict& v : c.images) h += image_comparison(c, v, pics);
  h += "<details><summary>no AO / with AO / AO only, parameters, timings</summary><div "
       "class=images>";
  h += figure(pics.img(file_of(c, "no_ao"), "", "no AO"), "no AO");
  h += figure(pics.img(file_of(c, "with_ao"), "", "with AO"), "with AO");
  h += figure(pics.img(file_of(c, "ao_only"), "", "AO only"), "AO only");
  h += "</div>";
  std::map<std::string, std::string> about;
  for (const auto& [k, v] : c.params) about[k] = v.is_string() ? v.get<std::string>() : v.dump();
  about["scene / view / technique"] = c.scene + " / " + c.view + " / " + c.technique;
  about["size"] = fmt::format("{}x{}", c.width, c.height);
  about["tolerance"] =
      fmt::format("mode {}, ≤ {}% mismatch, channel Δ ≤ {}", resemble::mode_name(c.tolerance.mode),
                  c.tolerance.max_mismatch_percent, c.tolerance.max_channel_delta);
  about["AO effect (ignoreLess / ignoreNothing)"] =
      fmt::format("{:.2f}% / {:.2f}%", c.ao_effect_less, c.ao_effect_nothing);
  h += kv_table(about);
  std::map<std::string, std::string> times;
  for (const renderer::PassTime& t : c.times) {
    times[t.pass] = fmt::format("GPU {:.3f} ms", t.gpu_ms);
  }
  h += kv_table(times) + "</details></section>\n";
  return h;
}

// The latest `aosuite sweep` beside this report (its default output, reports/sweep, next to
// reports/<suite>): linked, not embedded, since it is a separate run with its own date.
std::string sweep_link(const fs::path& report_dir) {
  const fs::path sweep = report_dir / ".." / "sweep";
  std::error_code ec;
  const auto when = fs::last_write_time(sweep / "sweep.md", ec);
  if (ec) {
    return "<p>No sweep next to this report yet: <code>aosuite sweep suites/sweep_ci.toml --out "
           "reports/sweep</code> measures each technique's run time against its error.</p>\n";
  }
  const auto age =
      std::chrono::duration_cast<std::chrono::hours>(fs::file_time_type::clock::now() - when);
  std::string links =
      "<a href=\"../sweep/sweep.md\">table</a>, <a href=\"../sweep/sweep.csv\">CSV</a>";
  for (const fs::directory_entry& e : fs::directory_iterator(sweep, ec)) {
    if (e.path().extension() != ".svg") continue;
    const std::string name = escape_markup(e.path().filename().string());
    links += fmt::format(", <a href=\"../sweep/{0}\">{0}</a>", name);
  }
  return fmt::format("<p>Latest sweep ({} h old): {}.</p>\n", age.count(), links);
}

}  // namespace

void write_html_report(const RunResults& run, const fs::path& report_dir,
                       const ReportOptions& /*options*/) {
  Pictures pics(report_dir / "cases");
  const Counts n = count(run);
  std::string body = fmt::format(
      "<h1>aosuite: {}</h1>\n<p>{} cases: <span class=PASS>{} passed</span>, <span "
      "class=FAIL>{} failed</span>, <span class=NEW>{} new</span>, <span class=ERROR>{} "
      "errors</span>. Suite <code>{}</code>{}. GL: {} (platform <code>{}</code>).</p>\n",
      escape_markup(run.suite), run.cases.size(), n.pass, n.fail, n.fresh, n.error,
      escape_markup(run.suite_file), run.shard.empty() ? "" : ", shard " + escape_markup(run.shard),
      escape_markup(run.gl), escape_markup(run.platform));
  body += "<h2>Cases</h2>\n" + summary_table(run);
  body += "<h2>How much AO changes the image (thesis Tables 11–14)</h2>\n" + ao_effect_table(run);
  body += "<h2>Run time against error</h2>\n" + sweep_link(report_dir);
  for (const CaseResult& c : run.cases) body += case_section(c, pics);
  const std::string page = fmt::format(
      "<!doctype html>\n<html lang=en><head><meta charset=utf-8><title>aosuite: {}</title>"
      "<style>{}</style></head><body>\n{}<script type=\"application/json\" id=images>{}</script>"
      "<script>{}</script></body></html>\n",
      escape_markup(run.suite), report_assets().at("report.css"), body, pics.json(),
      report_assets().at("report.js"));
  fs::create_directories(report_dir);
  write_file_atomic(report_dir / "index.html",
                    {reinterpret_cast<const unsigned char*>(page.data()), page.size()});
}

}  // namespace aosuite::harness

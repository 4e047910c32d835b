#include "harness/suite_file.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "common/file_io.hpp"
#include "common/toml_reader.hpp"
#include "harness/case_kind.hpp"
#include "harness/escape.hpp"
#include "image/picture.hpp"

namespace aosuite::harness {
namespace {

namespace fs = std::filesystem;

using Reader = TomlReader;

// A parameter as its TOML type: integer, float, boolean, string, or an array of them.
nlohmann::json typed_value(const Reader& r, const toml::node& n) {
  if (const toml::array* a = n.as_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const toml::node& e : *a) out.push_back(typed_value(r, e));
    return out;
  }
  if (auto s = n.value_exact<std::string>()) return *s;
  if (auto i = n.value_exact<std::int64_t>()) return *i;
  if (auto d = n.value_exact<double>()) return *d;
  if (auto b = n.value_exact<bool>()) return *b;
  r.fail(n.source(), "a parameter must be a number, a string, a boolean or an array of them");
}

void read_params(const Reader& r, const toml::node& n, std::map<std::string, std::string>& out,
                 std::map<std::string, toml::source_region>& where, nlohmann::json& values) {
  for (const auto& [key, value] : r.table(n, "params")) {
    values[std::string(key.str())] = typed_value(r, value);
    if (auto b = value.value_exact<bool>()) {
      out[std::string(key.str())] = *b ? "true" : "false";  // renderer cases refuse it by name
    } else {
      out[std::string(key.str())] = r.param(value);
    }
    where[std::string(key.str())] = value.source();
  }
}

// A metric's gates: `flip = { max_mean = 0.02, max_q3 = 0.3 }` (compare/metric.hpp says the keys).
metric::Gates read_gates(const Reader& r, const metric::Metric& m, const toml::node& n) {
  metric::Gates g{&m, {}, false};
  for (const auto& [key, value] : r.table(n, m.name)) {
    try {
      const double v =
          value.is_boolean() ? double(r.boolean(value, key.str())) : r.number(value, key.str());
      metric::add_gate(g, key.str(), v);
    } catch (const std::invalid_argument& e) {
      r.fail(value.source(), e.what());
    }
  }
  if (g.limits.empty()) r.fail(n.source(), fmt::format("{} sets no limit", m.name));
  return g;
}

// [tolerance.regions]: name = { color = [R, G, B], <metric> = { gates }, ... }.
std::vector<Region> read_regions(const Reader& r, const toml::node& n) {
  std::vector<Region> out;
  for (const auto& [name, value] : r.table(n, "regions")) {
    Region g;
    g.name = std::string(name.str());
    if (!valid_name(g.name))
      r.fail(value.source(), "region name '" + printable(g.name) + "' is not a name");
    const toml::table& tbl = r.table(value, g.name);
    const toml::node& color = r.required(tbl, "color");
    const toml::array* rgb = color.as_array();
    if (!rgb || rgb->size() != 3) r.fail(color.source(), "color is [R, G, B]");
    for (int c = 0; c < 3; ++c)
      g.color[std::size_t(c)] = r.integer((*rgb)[std::size_t(c)], "color", 0, 255);
    if (g.color == std::array<int, 3>{}) r.fail(color.source(), "black marks unclassified pixels");
    for (const Region& other : out)
      if (other.color == g.color) r.fail(color.source(), "two regions share a colour");
    for (const auto& [key, gates] : tbl) {
      if (key.str() == "color") continue;
      const metric::Metric* m = nullptr;
      try {
        m = &metric::find(key.str());
      } catch (const std::invalid_argument& e) {
        r.fail(gates.source(), e.what());
      }
      g.gates.push_back(read_gates(r, *m, gates));
    }
    if (g.gates.empty()) r.fail(value.source(), "region '" + g.name + "' has no metric gate");
    out.push_back(std::move(g));
  }
  return out;
}

// A two-sided budget, [min, max] with 0 <= min <= max <= hi (Mozilla's fuzzy(min-max) ranges).
std::pair<long long, long long> read_range(const Reader& r, const toml::node& n,
                                           std::string_view what, int hi) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2) r.fail(n.source(), fmt::format("{} must be [min, max]", what));
  const long long lo = r.integer((*a)[0], what, 0, hi), top = r.integer((*a)[1], what, 0, hi);
  if (lo > top) r.fail(n.source(), fmt::format("{}: min {} is above max {}", what, lo, top));
  return {lo, top};
}

// The registered metric a key names; else fails at the value, saying which keys the table
// takes (`keys`, then the metrics).
const metric::Metric& metric_key(const Reader& r, const toml::node& value, std::string_view key,
                                 std::string_view keys) {
  try {
    return metric::find(key);
  } catch (const std::invalid_argument&) {
    r.fail(value.source(), fmt::format("unknown key '{}' ({}the metrics {})", printable(key), keys,
                                       metric::names()));
  }
}

// [tolerance.warn]: max_mismatch_percent, max_channel_delta, differing_pixels (a maximum) and
// metric gates, as in the tolerance; each one it names warns.
WarnLimits read_warn(const Reader& r, const toml::node& n) {
  WarnLimits w;
  for (const auto& [key, value] : r.table(n, "warn")) {
    if (key.str() == "max_mismatch_percent") {
      w.max_mismatch_percent = r.number(value, "max_mismatch_percent");
      if (!(w.max_mismatch_percent >= 0 && w.max_mismatch_percent < 100))
        r.fail(value.source(), "warn.max_mismatch_percent must be 0..100 (below 100)");
    } else if (key.str() == "max_channel_delta") {
      w.max_channel_delta = r.integer(value, "max_channel_delta", 0, 254);
    } else if (key.str() == "differing_pixels") {
      w.max_differing_pixels = r.integer(value, "differing_pixels", 0, 1 << 30);
    } else {
      const metric::Metric& m = metric_key(r, value, key.str(),
                                           "warn keys: max_mismatch_percent, max_channel_delta, "
                                           "differing_pixels, and ");
      w.gates.push_back(read_gates(r, m, value));
    }
  }
  if (w.empty()) r.fail(n.source(), "[tolerance.warn] sets no limit");
  return w;
}

// A scalar TOML value as set_limit reads it.
std::string limit_text(const toml::node& n) {
  if (const auto* s = n.as_string()) return s->get();
  if (const auto* b = n.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* i = n.as_integer()) return std::to_string(i->get());
  if (const auto* f = n.as_floating_point()) return fmt::format("{}", f->get());
  return "(not a value)";
}

const std::string kToleranceKeys = std::string("tolerance keys: ") + comparison::kLimitKeys +
                                   ", channel_delta, differing_pixels, ignore, mask, "
                                   "foreground_only, regions, warn, float, and ";

// [tolerance]: the one tolerance (compare/tolerance.hpp). Each key sets the limit it names
// and leaves every other at its default: metric gates sit beside Resemble's gate, and a
// mismatch percentage keeps the channel limit.
void read_tolerance(const Reader& r, const fs::path& dir, const toml::node& n, Tolerance& t) {
  const toml::table& tbl = r.table(n, "tolerance");
  static constexpr std::string_view kOwnKeys[] = {
      "channel_delta",   "differing_pixels", "ignore", "mask",
      "foreground_only", "regions",          "warn",   "float"};
  for (const auto& [key, value] : tbl) {
    if (std::ranges::find(kOwnKeys, key.str()) != std::end(kOwnKeys)) continue;
    if (value.is_table() || value.is_array()) {
      const metric::Metric& m = metric_key(r, value, key.str(), kToleranceKeys);
      std::erase_if(t.gates, [&](const metric::Gates& g) { return g.metric == &m; });
      t.gates.push_back(read_gates(r, m, value));
      continue;
    }
    try {
      comparison::set_limit(t, key.str(), limit_text(value));
    } catch (const std::invalid_argument& e) {
      r.fail(value.source(),
             fmt::format("{} ({}the metrics {})", e.what(), kToleranceKeys, metric::names()));
    }
  }
  if (const toml::node* m = tbl.get("foreground_only"))
    t.foreground_only = r.boolean(*m, "foreground_only");
  if (const toml::node* m = tbl.get("regions")) t.regions = read_regions(r, *m);
  if (const toml::node* m = tbl.get("warn")) t.warn = read_warn(r, *m);
  if (const toml::node* f = tbl.get("float")) {
    // [tolerance.float]: metric gates for float images only.
    for (const auto& [key, value] : r.table(*f, "float")) {
      const metric::Metric& m = metric_key(r, value, key.str(), "[tolerance.float] takes ");
      std::erase_if(t.float_gates, [&](const metric::Gates& g) { return g.metric == &m; });
      t.float_gates.push_back(read_gates(r, m, value));
    }
  }
  if (const toml::node* m = tbl.get("channel_delta")) {
    if (tbl.get("max_channel_delta")) {
      r.fail(m->source(), "give channel_delta = [min, max] or max_channel_delta, not both");
    }
    const auto [lo, hi] = read_range(r, *m, "channel_delta", 255);
    t.min_channel_delta = static_cast<int>(lo), t.max_channel_delta = static_cast<int>(hi);
  }
  if (const toml::node* m = tbl.get("differing_pixels")) {
    if (m->is_integer()) {
      t.min_differing_pixels = 0;
      t.max_differing_pixels = r.integer(*m, "differing_pixels", 0, 1 << 30);
    } else {
      std::tie(t.min_differing_pixels, t.max_differing_pixels) =
          read_range(r, *m, "differing_pixels", 1 << 30);
    }
  }
  if (const toml::node* m = tbl.get("ignore")) {
    t.ignore.clear();
    const toml::array* boxes = m->as_array();
    if (!boxes) r.fail(m->source(), "ignore must be an array of [left, top, right, bottom]");
    for (const toml::node& b : *boxes) {
      const toml::array* box = b.as_array();
      if (!box || box->size() != 4) r.fail(b.source(), "a box is [left, top, right, bottom]");
      resemble::Box out;
      out.left = r.integer((*box)[0], "left", 0, 1 << 20);
      out.top = r.integer((*box)[1], "top", 0, 1 << 20);
      out.right = r.integer((*box)[2], "right", 0, 1 << 20);
      out.bottom = r.integer((*box)[3], "bottom", 0, 1 << 20);
      if (out.right < out.left || out.bottom < out.top)
        r.fail(b.source(), "box has right < left or bottom < top");
      t.ignore.push_back(out);
    }
  }
  if (const toml::node* m = tbl.get("mask")) {
    t.mask = dir / r.string(*m, "mask");
    if (!fs::is_regular_file(t.mask)) r.fail(m->source(), "no mask image " + t.mask.string());
  }
}

// What [defaults] and every [[case]] may say, whatever makes its images.
struct Common {
  int width = 320, height = 180;  // a rendered scene's size unless the suite says
  bool width_given = false, height_given = false;
  std::map<std::string, std::string> params;
  std::map<std::string, toml::source_region> param_at;
  nlohmann::json values = nlohmann::json::object();
  Tolerance tolerance;
};
constexpr std::string_view kCommonKeys[] = {"width", "height", "params", "tolerance"};
constexpr std::string_view kImageCaseKeys[] = {"name", "command", "outputs", "inputs",
                                               "env",  "timeout", "files"};

void read_common(const Reader& r, const fs::path& dir, const toml::table& t, Common& c) {
  if (const toml::node* n = t.get("width")) {
    c.width = r.integer(*n, "width", 1, 16384);
    c.width_given = true;
  }
  if (const toml::node* n = t.get("height")) {
    c.height = r.integer(*n, "height", 1, 16384);
    c.height_given = true;
  }
  if (const toml::node* n = t.get("params")) read_params(r, *n, c.params, c.param_at, c.values);
  if (const toml::node* n = t.get("tolerance")) read_tolerance(r, dir, *n, c.tolerance);
}

// An image's name from its file: the stem, which names golden and report files.
std::string image_name(const Reader& r, const toml::node& at, const fs::path& file) {
  if (!is_image_name(file)) {
    r.fail(at.source(), "'" + printable(file.string()) + "' is not an image file (aosuite reads " +
                            kImageFormats + ")");
  }
  const std::string stem = file.stem().string();
  if (!valid_name(stem)) {
    r.fail(at.source(), "image file name '" + printable(file.filename().string()) +
                            "' must be letters, digits, - _ . and not start with '.'");
  }
  return stem;
}

// Whether an image's name would clash with the report's own files beside its image.
bool names_a_report_file(std::string_view name) {
  static constexpr std::string_view kReportPrefixes[] = {
      "golden_", "diff_", "thumb_", "heat_", "regions_", "ignored_", "abs_", "signed_"};
  // attempt<k>_: a retried case's failing attempt (check --retries).
  const bool attempt = name.starts_with("attempt") && name.size() > 7 &&
                       std::isdigit(static_cast<unsigned char>(name[7]));
  return name == "case" || attempt || std::ranges::any_of(kReportPrefixes, [&](std::string_view p) {
           return name.starts_with(p);
         });
}

// A relative path that stays inside its folder.
fs::path inside_path(const Reader& r, const toml::node& at, const std::string& text) {
  const fs::path p = fs::path(text).lexically_normal();
  if (text.empty() || p.is_absolute() || p.empty() || *p.begin() == "..") {
    r.fail(at.source(), "'" + printable(text) + "' must be a relative path inside the folder");
  }
  return p;
}

// f(), which may load the registered kinds: a kind that cannot be loaded (a build without the
// AO bench) is an error at `at`, naming the suite file.
template <typename F>
auto loading_kinds(const Reader& r, const toml::source_region& at, F f) {
  try {
    return f();
  } catch (const std::runtime_error& e) {
    r.fail(at, e.what());
  }
}

// Refuses a key of `t` that is neither shared nor in `own`, loading the registered kinds
// first if one is unknown (it may be theirs).
void only_known_keys(const Reader& r, const toml::table& t, std::span<const std::string_view> own,
                     std::vector<std::string_view> (*kinds_keys)()) {
  const auto known = [&] {
    std::vector<std::string_view> keys(std::begin(kCommonKeys), std::end(kCommonKeys));
    keys.insert(keys.end(), own.begin(), own.end());
    for (std::string_view k : kinds_keys()) keys.push_back(k);
    return keys;
  };
  std::vector<std::string_view> keys = known();
  const bool unknown = std::ranges::any_of(
      t, [&](const auto& kv) { return std::ranges::find(keys, kv.first.str()) == keys.end(); });
  if (unknown && loading_kinds(r, t.source(), load_kinds)) keys = known();
  r.only_keys(t, keys);
}

// A [[case]] with `command` or `files`.
// "case id 'aaaa…' is 230 characters long, ...": the name (its start, when long) and why.
std::string bad_name(std::string_view what, std::string_view name) {
  const bool cut = name.size() > 60;
  return fmt::format("{} '{}{}' {}", what, printable(name.substr(0, 60)), cut ? "..." : "",
                     name_problem(name));
}

Case image_case(const Reader& r, const fs::path& dir, const toml::table& t, Common c,
                bool follow_links) {
  r.only_keys(t, [] {
    std::vector<std::string_view> keys(std::begin(kCommonKeys), std::end(kCommonKeys));
    keys.insert(keys.end(), std::begin(kImageCaseKeys), std::end(kImageCaseKeys));
    return keys;
  }());
  read_common(r, dir, t, c);
  const toml::node* name = t.get("name");
  if (!name) r.fail(t.source(), "an image case needs name = \"<case id>\"");
  Case k;
  k.id = r.string(*name, "name");
  if (!valid_name(k.id)) r.fail(name->source(), bad_name("case id", k.id));
  auto src = std::make_shared<ImageSource>();
  src->dir = fs::absolute(dir).lexically_normal();
  src->follow_links = follow_links;
  // An image case has the size of its images; width and height are only what the suite tells
  // its command ({width}, {height}), both or neither: never a default standing in for one.
  if (c.width_given != c.height_given) {
    r.fail(t.source(),
           "an image case gives width and height together (its command reads them as "
           "{width} and {height}), or neither");
  }
  if (c.width_given) k.width = c.width, k.height = c.height;
  k.tolerance = c.tolerance;
  if (k.tolerance.foreground_only) {
    r.fail(t.source(),
           "foreground_only needs a rendered scene (its G-buffer says which pixels "
           "are geometry); an image case has none");
  }
  k.param_overrides = c.params, k.values = c.values;
  const toml::node* command = t.get("command");
  const toml::node* files = t.get("files");
  if (command && files) r.fail(files->source(), "a case has command or files, not both");
  if (command) {
    src->command = r.strings(*command, "command");
    const toml::node* outputs = t.get("outputs");
    if (!outputs) {
      r.fail(command->source(), "a command case needs outputs = [\"<file it writes>.png\", ...]");
    }
    for (const std::string& o : r.strings(*outputs, "outputs")) {
      src->outputs.push_back(inside_path(r, *outputs, o).string());
      k.images.push_back(image_name(r, *outputs, o));
    }
    if (const toml::node* n = t.get("inputs")) {
      for (const std::string& in : r.strings(*n, "inputs", true)) {
        src->inputs.push_back(dir / in);
        std::error_code ec;
        if (!fs::exists(src->inputs.back(), ec)) {
          r.fail(n->source(), "no input file " + printable(src->inputs.back().string()));
        }
        if (!fs::is_regular_file(src->inputs.back(), ec)) {
          r.fail(n->source(), "input " + printable(src->inputs.back().string()) +
                                  " is not a regular file (a device, FIFO or folder)");
        }
      }
    }
    if (const toml::node* n = t.get("env")) src->env = r.strings(*n, "env", true);
    src->declared = t.get("inputs") || t.get("env");
    if (const toml::node* n = t.get("timeout")) {
      src->timeout_seconds = r.positive(*n, "timeout");
    }
  } else {
    for (const char* key : {"outputs", "inputs", "env", "timeout"}) {
      if (const toml::node* n = t.get(key)) {
        r.fail(n->source(), std::string("'") + key + "' belongs to a command case");
      }
    }
    for (const std::string& f : r.strings(*files, "files")) {
      src->files.push_back(dir / f);
      k.images.push_back(image_name(r, *files, f));
    }
  }
  // Each image keeps its file type: 8-bit ones are judged by Resemble and the metrics, 16-bit
  // and float ones by the metrics ([tolerance.float]), else sample for sample. One render written
  // as frame.png and frame.exr is two images, named apart by their types: frame_png, frame_exr.
  const std::vector<std::string>& names =
      command ? src->outputs : std::vector<std::string>(src->files.begin(), src->files.end());
  if (names.empty()) r.fail(t.source(), "an image case needs at least one image");
  const auto type = [](const std::string& file) { return fs::path(file).extension().string(); };
  std::map<std::string, std::set<std::string>> types;  // stem -> its files' types
  for (const std::string& n : names) types[fs::path(n).stem().string()].insert(type(n));
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string ext = type(names[i]);
    if (types.at(k.images[i]).size() > 1) k.images[i] += "_" + ext.substr(1);
    src->exts[k.images[i]] = ext;
    if (names_a_report_file(k.images[i])) {
      r.fail((command ? *t.get("outputs") : *files).source(),
             "image '" + printable(names[i]) + "' would be named '" + k.images[i] +
                 "', which must not be 'case' nor start with golden_, diff_, thumb_, heat_, "
                 "regions_, ignored_, abs_, signed_ or attempt<k> (the report's files)");
    }
  }
  std::set<std::string> seen;
  for (const std::string& image : k.images) {
    if (!seen.insert(image).second) {
      r.fail((command ? *t.get("outputs") : *files).source(),
             "two images named '" + image + "' (their file stems must differ)");
    }
  }
  if (command) {
    k.source = src;
    std::map<std::string, std::string> values = command_placeholders(k);
    values["out"] = "/out";
    for (const std::string& arg : src->command) {
      try {
        expand_placeholders(arg, values, false);
      } catch (const std::invalid_argument& e) {
        r.fail(command->source(), e.what());
      }
    }
  }
  k.source = std::move(src);
  return k;
}

}  // namespace

Suite load_suite(const fs::path& file) {
  toml::table root;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    throw FileError(file.string() +
                    (fs::exists(file, ec) ? ": not a regular file" : ": no such suite file"));
  }
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    const auto& at = e.source().begin;
    throw std::runtime_error(
        fmt::format("{}:{}:{}: {}", file.string(), at.line, at.column, e.description()));
  }
  const Reader r(file);
  const fs::path dir = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  r.only_keys(root, {"name", "goldens", "follow_links", "defaults", "case"});

  Suite suite;
  suite.file = file;
  suite.name = file.stem().string();
  if (const toml::node* n = root.get("name")) suite.name = r.string(*n, "name");
  if (!valid_name(suite.name)) {
    r.fail(root.get("name") ? root.get("name")->source() : root.source(),
           bad_name("suite name", suite.name));
  }
  // Beside the suite file, whatever the current directory: a suite checked from elsewhere
  // finds its goldens, and bless never writes a second tree there.
  suite.goldens = dir / "goldens" / suite.name;
  if (const toml::node* n = root.get("goldens")) suite.goldens = dir / r.string(*n, "goldens");
  suite.goldens = suite.goldens.lexically_normal();
  if (const toml::node* n = root.get("follow_links"))
    suite.follow_links = r.boolean(*n, "follow_links");

  Common defaults;
  const toml::table* defaults_table = nullptr;
  if (const toml::node* n = root.get("defaults")) {
    defaults_table = &r.table(*n, "defaults");
    only_known_keys(r, *defaults_table, {}, kinds_default_keys);
    read_common(r, dir, *defaults_table, defaults);
  }
  const toml::array* cases = root.get_as<toml::array>("case");
  if (!cases || cases->empty()) r.fail(root.source(), "a suite needs at least one [[case]]");

  std::set<std::string> ids;
  std::map<std::string, std::shared_ptr<const void>> memo;
  for (int index = 0; const toml::node& node : *cases) {
    const toml::table& t = r.table(node, "case");
    std::vector<Case> made;
    if (t.get("command") || t.get("files")) {
      made.push_back(image_case(r, dir, t, defaults, suite.follow_links));
    } else {
      const CaseKind* kind = loading_kinds(r, t.source(), [&] { return kind_for(t); });
      if (!kind) {
        std::string kinds;
        for (const CaseKind* k : harness::kinds()) kinds += fmt::format("{} = ..., ", k->key());
        r.fail(t.source(), fmt::format("a case needs {}command = [...] or files = [...]", kinds));
      }
      only_known_keys(r, t, {std::begin(kImageCaseKeys), 1}, kinds_case_keys);
      Common c = defaults;
      read_common(r, dir, t, c);
      CaseTable table{r, dir, defaults_table, t, {}, c.param_at, {}, memo};
      table.base.kind = kind;
      table.base.width = c.width, table.base.height = c.height;
      table.base.tolerance = c.tolerance;
      table.base.param_overrides = c.params, table.base.values = c.values;
      if (const toml::node* n = t.get("name")) table.suffix = "-" + r.string(*n, "name");
      kind->expand(table, made);
    }
    for (Case& k : made) {
      if (!valid_name(k.id)) r.fail(t.source(), bad_name("case id", k.id));
      if (!ids.insert(k.id).second) r.fail(t.source(), "duplicate case '" + k.id + "'");
      k.table = index;
      suite.cases.push_back(std::move(k));
    }
    ++index;
  }
  return suite;
}

}  // namespace aosuite::harness

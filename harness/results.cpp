#include "harness/results.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "harness/escape.hpp"
#include "image/image_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A whole number that fits an int. A shard's results.json may hold anything there, and
// converting a JSON float beyond int's range to int is undefined behaviour.
int int_at(const json& j, const char* key) {
  const json& v = j.at(key);
  if (v.is_number_unsigned() ? v.get<std::uint64_t>() <= INT_MAX
                             : v.is_number_integer() && v.get<std::int64_t>() >= INT_MIN &&
                                   v.get<std::int64_t>() <= INT_MAX) {
    return v.get<int>();
  }
  throw std::runtime_error(std::string("'") + key + "' must be an integer that fits an int");
}

int int_or(const json& j, const char* key, int fallback) {
  return j.contains(key) ? int_at(j, key) : fallback;
}

json to_json(const ImageVerdict& v) {
  json metrics = json::object(), gates = json::array();
  for (const metric::Measurement& m : v.measured) metrics[m.metric] = m.json();
  for (const metric::Outcome& o : v.outcomes) gates.push_back(metric::to_json(o));
  return {{"image", v.image},
          {"metrics", metrics},
          {"gates", gates},
          {"status", status_name(v.status)},
          {"identical", v.identical},
          {"mismatch_percent", v.mismatch_percent},
          {"mismatch_text", v.mismatch_text},
          {"max_channel_delta", v.max_channel_delta},
          {"differing_pixels", v.differing_pixels},
          {"mean_shift", v.mean_shift},
          {"mean_delta", v.mean_delta},
          {"kinds", {v.expected_kind, v.actual_kind}},
          {"largest", {{"value", v.largest.value}, {"x", v.largest.x}, {"y", v.largest.y}}},
          {"changes", comparison::changes_json(v.changes)},
          {"stale", v.stale},
          {"golden", printable(v.golden.string())},
          {"golden_hash", v.golden_hash},
          {"comparable", v.comparable},
          {"message", printable(v.message)}};
}

ImageVerdict verdict_from_json(const json& j) {
  ImageVerdict v;
  v.image = j.at("image");
  v.status = parse_status(j.at("status").get<std::string>());
  v.identical = j.at("identical");
  v.mismatch_percent = j.at("mismatch_percent");
  v.mismatch_text = j.at("mismatch_text");
  v.max_channel_delta = int_at(j, "max_channel_delta");
  v.differing_pixels = j.value("differing_pixels", 0LL);
  v.mean_shift = j.value("mean_shift", 0.0), v.mean_delta = j.value("mean_delta", 0.0);
  if (const auto ch = j.find("changes"); ch != j.end())
    v.changes = comparison::changes_from_json(*ch);
  if (const auto l = j.find("largest"); l != j.end()) {  // absent in older results
    v.largest = {l->at("value").get<double>(), int_at(*l, "x"), int_at(*l, "y")};
  }
  v.stale = j.value("stale", std::vector<std::string>());
  v.golden = j.at("golden").get<std::string>();
  // Absent in older results: `tolerances suggest` then asks for a new run.
  v.golden_hash = j.value("golden_hash", std::string());
  v.comparable = j.value("comparable", false);
  v.message = j.at("message");
  const json metrics = j.value("metrics", json::object()), gates = j.value("gates", json::array());
  for (const auto& [name, m] : metrics.items())
    v.measured.push_back(metric::measurement_from_json(metric::find(name), m));
  for (const json& o : gates) v.outcomes.push_back(metric::outcome_from_json(o));
  return v;
}

}  // namespace

json to_json(const CaseResult& c) {
  json images = json::array(), times = json::array(), ignore = json::array();
  json attempts = json::array();
  for (const Attempt& a : c.failed_attempts) {
    attempts.push_back(
        {{"status", status_name(a.status)}, {"message", printable(a.message)}, {"files", a.files}});
  }
  for (const ImageVerdict& v : c.images) images.push_back(to_json(v));
  for (const Timing& t : c.times) times.push_back({{"stage", t.stage}, {"ms", t.ms}});
  json labels = json::array();
  for (const auto& [k, v] : c.labels) labels.push_back({printable(k), printable(v)});
  for (const resemble::Box& b : c.tolerance.ignore)
    ignore.push_back({b.left, b.top, b.right, b.bottom});
  const auto gates_of = [](const std::vector<metric::Gates>& list) {
    json out = json::object();
    for (const metric::Gates& g : list) out[std::string(g.metric->name)] = to_json(g);
    return out;
  };
  const json gates = gates_of(c.tolerance.gates);
  json regions = json::object();
  for (const Region& r : c.tolerance.regions)
    regions[r.name] = {{"color", r.color}, {"gates", gates_of(r.gates)}};
  json params = json::object();
  for (const auto& [k, v] : c.params)
    params[k] = v.is_string() ? json(printable(v.get<std::string>())) : v;
  return {
      {"id", c.id},
      {"kind", c.kind},
      {"source", printable(c.source)},
      {"exit_status", c.exit_status},
      {"attempts", c.attempts},
      {"failed_attempts", attempts},
      {"command_stderr", printable_lines(c.command_stderr)},
      {"labels", labels},
      {"width", c.width},
      {"height", c.height},
      {"params", params},
      {"tolerance",
       {{"resemble", c.tolerance.resemble},
        {"foreground_only", c.tolerance.foreground_only},
        {"gates", gates},
        {"regions", regions},
        {"mode", resemble::mode_name(c.tolerance.mode)},
        {"max_mismatch_percent", c.tolerance.max_mismatch_percent},
        {"max_channel_delta", c.tolerance.max_channel_delta},
        {"min_channel_delta", c.tolerance.min_channel_delta},
        {"differing_pixels", {c.tolerance.min_differing_pixels, c.tolerance.max_differing_pixels}},
        {"ignore", ignore},
        {"mask", printable(c.tolerance.mask.string())},
        {"warn",
         {{"max_mismatch_percent", c.tolerance.warn.max_mismatch_percent},
          {"max_channel_delta", c.tolerance.warn.max_channel_delta},
          {"max_differing_pixels", c.tolerance.warn.max_differing_pixels},
          {"gates", gates_of(c.tolerance.warn.gates)}}}}},
      {"status", status_name(c.status)},
      {"message", printable(c.message)},
      {"images", images},
      {"files", c.files},
      {"times", times},
      {"figures", c.figures},
      {"input_hash", c.input_hash},
      {"judge_hash", c.judge_hash},
      {"image_hashes", c.image_hashes},
      {"pass_hashes", c.pass_hashes},
      {"reused", c.reused},
      {"not_reused", c.not_reused},
      {"deleted", c.deleted},
      {"images_left_out", c.images_left_out},
      {"seconds", c.seconds},
      {"bless_command", printable(c.bless_command)}};
}

CaseResult case_from_json(const json& j) {
  CaseResult c;
  c.id = j.at("id");
  if (!valid_name(c.id))
    throw std::runtime_error("case id '" + printable(c.id) + "' is not a name");
  for (const json& l : j.at("labels")) c.labels.emplace_back(l.at(0), l.at(1));
  c.width = int_at(j, "width"), c.height = int_at(j, "height");
  for (const auto& [k, v] : j.at("params").items()) c.params[k] = v;
  c.kind = j.at("kind");
  c.source = j.value("source", std::string());
  c.exit_status = int_or(j, "exit_status", -1);
  c.attempts = int_or(j, "attempts", 1);
  c.command_stderr = j.value("command_stderr", std::string());
  const json& t = j.at("tolerance");
  c.tolerance.mode = resemble::parse_mode(t.at("mode").get<std::string>());
  c.tolerance.max_mismatch_percent = t.at("max_mismatch_percent");
  c.tolerance.max_channel_delta = int_at(t, "max_channel_delta");
  c.tolerance.min_channel_delta = t.value("min_channel_delta", 0);
  const json differing = t.value("differing_pixels", json::array({0, -1}));
  c.tolerance.min_differing_pixels = differing.at(0),
  c.tolerance.max_differing_pixels = differing.at(1);
  // at(), not []: a box of fewer than four numbers must not be read past its end.
  for (const json& b : t.at("ignore")) {
    c.tolerance.ignore.push_back({b.at(0), b.at(1), b.at(2), b.at(3)});
  }
  c.tolerance.mask = t.at("mask").get<std::string>();
  c.tolerance.resemble = t.value("resemble", true);
  c.tolerance.foreground_only = t.value("foreground_only", false);
  const auto gates_from = [](const json& list, std::vector<metric::Gates>& out) {
    for (const auto& [name, g] : list.items())
      out.push_back(metric::gates_from_json(metric::find(name), g));
  };
  gates_from(t.value("gates", json::object()), c.tolerance.gates);
  if (const auto w = t.find("warn"); w != t.end()) {
    c.tolerance.warn.max_mismatch_percent = w->at("max_mismatch_percent");
    c.tolerance.warn.max_channel_delta = int_at(*w, "max_channel_delta");
    c.tolerance.warn.max_differing_pixels = w->at("max_differing_pixels");
    gates_from(w->at("gates"), c.tolerance.warn.gates);
  }
  const json regions = t.value("regions", json::object());
  for (const auto& [name, r] : regions.items()) {
    Region region{name, r.at("color").get<std::array<int, 3>>(), {}};
    gates_from(r.at("gates"), region.gates);
    c.tolerance.regions.push_back(std::move(region));
  }
  c.status = parse_status(j.at("status").get<std::string>());
  c.message = j.at("message");
  for (const json& v : j.at("images")) c.images.push_back(verdict_from_json(v));
  // A report's files, each a plain name inside its case's folder (a merge copies that folder).
  const auto files_at = [&](const json& files) {
    auto out = files.get<std::map<std::string, std::string>>();
    for (const auto& [role, file] : out) {
      const fs::path f(file);
      if (f.parent_path() != c.id || !valid_name(f.filename().string())) {
        throw std::runtime_error("case '" + c.id + "': file '" + printable(file) +
                                 "' is not inside its case folder");
      }
    }
    return out;
  };
  c.files = files_at(j.at("files"));
  for (const json& a : j.value("failed_attempts", json::array())) {
    c.failed_attempts.push_back({parse_status(a.at("status").get<std::string>()), a.at("message"),
                                 files_at(a.at("files"))});
  }
  for (const json& t2 : j.at("times")) c.times.push_back({t2.at("stage"), t2.at("ms")});
  c.figures = j.at("figures").get<std::map<std::string, double>>();
  c.input_hash = j.at("input_hash"), c.judge_hash = j.at("judge_hash");
  // Absent in older results: then nothing is reused, which only costs a render.
  c.image_hashes = j.value("image_hashes", std::map<std::string, std::string>{});
  c.pass_hashes = j.value("pass_hashes", decltype(c.pass_hashes){});
  c.reused = j.at("reused"), c.seconds = j.at("seconds");
  c.not_reused = j.value("not_reused", "");
  c.deleted = j.value("deleted", false);
  c.images_left_out = j.value("images_left_out", false);
  c.bless_command = j.at("bless_command");
  return c;
}

json to_json(const RunResults& r) {
  json cases = json::array();
  for (const CaseResult& c : r.cases) cases.push_back(to_json(c));
  return {{"suite", r.suite},
          {"suite_file", printable(r.suite_file)},
          {"goldens", printable(r.goldens)},
          {"expected_folder", printable(r.expected_folder)},
          {"environment", printable(r.environment)},
          {"platform", r.platform},
          {"bless_prefix", printable(r.bless_prefix)},
          {"shard", r.shard},
          {"approve_prefix", printable(r.approve_prefix)},
          {"cases", cases}};
}

std::string absolute_path(const fs::path& p) { return fs::absolute(p).lexically_normal().string(); }

RunResults run_from_json(const json& j) {
  RunResults r;
  r.suite = j.at("suite"), r.suite_file = j.at("suite_file"), r.environment = j.at("environment");
  r.platform = j.at("platform"), r.shard = j.at("shard");
  r.goldens = j.value("goldens", std::string());
  r.expected_folder = j.value("expected_folder", std::string());
  r.bless_prefix = j.value("bless_prefix", std::string());
  r.approve_prefix = j.value("approve_prefix", std::string());
  if (!valid_name(r.suite))
    throw std::runtime_error("suite '" + printable(r.suite) + "' is not a name");
  for (const json& c : j.at("cases")) r.cases.push_back(case_from_json(c));
  return r;
}

void keep_in_report(const fs::path& file, const std::vector<unsigned char>& bytes) {
  std::error_code ec;
  if (fs::is_regular_file(fs::symlink_status(file, ec)) &&
      fs::file_size(file, ec) == bytes.size() && !ec && read_file(file) == bytes) {
    return;
  }
  write_report_file(file, bytes);
}

RunResults read_results(const fs::path& dir) {
  const fs::path file = dir / "results.json";
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(file, ec))) {
    throw std::runtime_error(file.string() + ": cannot read (no run results there)");
  }
  const std::vector<unsigned char> bytes = read_regular_file(file);
  try {
    return run_from_json(json::parse(bytes));
  } catch (const std::exception& e) {
    throw std::runtime_error(file.string() + ": malformed run results: " + e.what());
  }
}

void write_report_file(const fs::path& path, std::span<const unsigned char> bytes) {
  static std::atomic<unsigned> serial{0};
  const std::string tmp =
      (path.parent_path() /
       fmt::format(".{}.tmp-{}-{}", path.filename().string(), ::getpid(), serial++))
          .string();
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(errno));
  }
  const auto fail = [&](const char* what) {
    const int saved = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    throw std::runtime_error(path.string() + ": " + what + ": " + std::strerror(saved));
  };
  for (std::size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail("cannot write");
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(saved));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    throw std::runtime_error(path.string() + ": cannot rename into place: " + std::strerror(saved));
  }
}

void write_results(const fs::path& dir, const RunResults& r) {
  const std::string text = to_json(r).dump(1) + "\n";
  write_report_file(dir / "results.json",
                    {reinterpret_cast<const unsigned char*>(text.data()), text.size()});
}

Counts count(const RunResults& r) {
  Counts n;
  for (const CaseResult& c : r.cases) {
    n.deleted += c.deleted;
    switch (c.status) {
      case Status::kPass:
        ++n.pass;
        break;
      case Status::kFail:
        ++n.fail;
        break;
      case Status::kNew:
        ++n.fresh;
        break;
      case Status::kError:
        ++n.error;
        break;
      case Status::kFlaky:
        ++n.flaky;
        break;
      case Status::kWarn:
        ++n.warn;
        break;
    }
  }
  return n;
}

int exit_code(const Counts& c) { return c.error ? 2 : (c.fail || c.fresh) ? 1 : 0; }

}  // namespace aosuite::harness

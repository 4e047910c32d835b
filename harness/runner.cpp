#include "harness/runner.hpp"

#include <fmt/format.h>
#include <string.h>  // sigabbrev_np, sigdescr_np

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <optional>
#include <span>
#include <stdexcept>
#include <thread>

#include "common/content_hash.hpp"
#include "harness/case_hash.hpp"
#include "harness/case_kind.hpp"
#include "harness/command.hpp"
#include "harness/escape.hpp"
#include "harness/goldens.hpp"
#include "harness/invocation.hpp"
#include "harness/report_images.hpp"
#include "image/exr_file.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

void set_shard(Selection& s, const std::string& text) {
  std::string spec = text;
  if (spec.empty()) {
    const char* index = std::getenv("GTEST_SHARD_INDEX");
    const char* total = std::getenv("GTEST_TOTAL_SHARDS");
    if (!index || !total) return;
    spec = fmt::format("{}/{}", index, total);
  }
  const std::size_t slash = spec.find('/');
  try {
    std::size_t used_i = 0, used_n = 0;
    s.shard_index = std::stoi(spec.substr(0, slash), &used_i);
    s.shard_count = std::stoi(spec.substr(slash + 1), &used_n);
    if (slash == std::string::npos || used_i != slash || used_n != spec.size() - slash - 1) {
      throw std::invalid_argument("");
    }
  } catch (const std::exception&) {
    throw std::invalid_argument("shard '" + spec + "' is not i/n");
  }
  if (s.shard_count < 1 || s.shard_index < 0 || s.shard_index >= s.shard_count) {
    throw std::invalid_argument("shard '" + spec + "' needs 0 <= i < n");
  }
}

std::vector<const Case*> select(const Suite& suite, const Selection& s) {
  std::optional<std::regex> re;
  if (!s.filter.empty()) {
    try {
      re.emplace(s.filter, std::regex::ECMAScript);
    } catch (const std::regex_error& e) {
      throw std::invalid_argument("--filter '" + s.filter + "': " + e.what());
    }
  }
  std::vector<const Case*> kept;
  for (const Case& c : suite.cases) {
    if (!re || std::regex_search(c.id, *re)) kept.push_back(&c);
  }
  std::vector<const Case*> out;
  for (std::size_t i = 0; i < kept.size(); ++i) {
    if (static_cast<int>(i % s.shard_count) == s.shard_index) out.push_back(kept[i]);
  }
  return out;
}

std::string bless_prefix(const Suite& suite) {
  if (!suite.bless_prefix.empty()) return suite.bless_prefix;
  std::string out = program_command() + " bless " + shell_quote(suite.file.string());
  if (suite.goldens_given) out += " --goldens " + shell_quote(suite.goldens.string());
  return out;
}

std::string exact_filter(const std::vector<std::string>& ids) {
  std::string alternatives;
  for (const std::string& id : ids) {
    if (!alternatives.empty()) alternatives += '|';
    for (const char ch : id) {
      if (std::string_view("\\^$.|?*+()[]{}").find(ch) != std::string_view::npos) {
        alternatives += '\\';
      }
      alternatives += ch;
    }
  }
  return ids.size() == 1 ? "^" + alternatives + "$" : "^(" + alternatives + ")$";
}

std::string bless_command(std::string_view prefix, const std::vector<std::string>& ids) {
  return fmt::format("{} --filter {}", prefix, shell_quote(exact_filter(ids)));
}

namespace {

// A case's images, fresh or reused from the report folder.
using Rendered = CaseImages;

// One thread's makers, one per kind, each made when a case of its kind first needs it (a GL
// context costs time and memory: an image-only run makes none).
struct Makers {
  std::map<const CaseKind*, std::unique_ptr<Maker>> by_kind;
  Maker& get(const CaseKind* kind) {
    std::unique_ptr<Maker>& m = by_kind[kind];
    if (!m) m = kind->maker(nullptr);
    return *m;
  }
};

// The report folder's cache.json: the last result of every case run there (any selection), by
// id: what tells an unchanged case. One file, read once and written once per run (thousands of
// small files cost more than their bytes). A damaged cache only costs re-running.
using Cache = std::map<std::string, CaseResult>;

Cache load_cache(const fs::path& report_dir) {
  Cache cache;
  std::ifstream in(report_dir / "cache.json");
  if (!in) return cache;
  try {
    for (const nlohmann::json& j : nlohmann::json::parse(in)) {
      CaseResult c = case_from_json(j);
      cache[c.id] = std::move(c);
    }
  } catch (const std::exception&) {
    cache.clear();
  }
  return cache;
}

// What only describes one run (its time, whether it was reused) is left out.
void save_cache(const fs::path& report_dir, Cache cache, const std::vector<CaseResult>& ran) {
  for (const CaseResult& r : ran) {
    CaseResult& saved = cache[r.id] = r;
    saved.seconds = 0, saved.reused = false, saved.not_reused.clear();
  }
  nlohmann::json all = nlohmann::json::array();
  for (const auto& [id, c] : cache) all.push_back(to_json(c));
  const std::string text = all.dump() + "\n";
  write_report_file(report_dir / "cache.json",
                    {reinterpret_cast<const unsigned char*>(text.data()), text.size()});
}

// The file type of a case's image: an image case's own (".png", folder mode's ".exr"), else
// what its kind says.
std::string ext_of(const Case& c, std::string_view image) {
  return c.source ? c.source->ext : c.made->ext(image);
}

// The images a case keeps in its report folder: an image case's own, else its kind's.
std::vector<std::string> kept_images(const Case& c) {
  return c.source ? c.images : c.made->kept_images(c);
}

bool is_shell(const std::string& program) {
  const std::string base = fs::path(program).filename().string();
  return base == "sh" || base == "bash" || base == "dash" || base == "zsh" || base == "ksh";
}

std::string last_line(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.remove_suffix(1);
  const std::size_t nl = text.rfind('\n');
  return std::string(nl == std::string_view::npos ? text : text.substr(nl + 1));
}

// How a suite allows links out of its folders (check_no_link_out's message).
constexpr std::string_view kFollowLinks = "`follow_links = true` in the suite allows it";

// A command's output folder ({out}): case_dir/.out-XXXXXX, made empty for this run alone (no
// two runs, nor a run and a folder left behind by a killed one, ever share it) and removed
// once its images are read.
class Staging {
 public:
  explicit Staging(const fs::path& case_dir) {
    std::string p = (fs::absolute(case_dir).lexically_normal() / ".out-XXXXXX").string();
    if (!::mkdtemp(p.data())) {
      throw FileError(fmt::format("{}: cannot make the command's output folder: {}",
                                  case_dir.string(), std::strerror(errno)));
    }
    path_ = p;
  }
  ~Staging() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// An image case's images: its command's outputs or its files, checked as PNG and copied into
// `case_dir`. The command runs in a staging folder of its own ({out}), which starts empty.
void produce_images(const Case& c, const fs::path& case_dir, CaseResult& r, Rendered& out) {
  const ImageSource& src = *c.source;
  fs::create_directories(case_dir);
  std::vector<fs::path> from = src.files;
  std::optional<Staging> staging;
  if (!src.command.empty()) {
    const fs::path& work = staging.emplace(case_dir).path();
    std::map<std::string, std::string> values = command_placeholders(c);
    values["out"] = work.string();
    std::vector<std::string> argv;
    for (std::size_t i = 0; i < src.command.size(); ++i) {
      // Inside `sh -c SCRIPT` what is inserted is shell-quoted: no field is ever shell syntax.
      const bool quote = i > 0 && is_shell(src.command[0]) && src.command[i - 1] == "-c";
      argv.push_back(expand_placeholders(src.command[i], values, quote));
    }
    if (argv[0].find('/') != std::string::npos && fs::path(argv[0]).is_relative()) {
      argv[0] = (src.dir / argv[0]).lexically_normal().string();  // relative to the suite
    }
    const CommandOutcome run =
        run_command(argv, work, case_dir / "stdout.txt", case_dir / "stderr.txt",
                    src.timeout_seconds, {"AOSUITE_OUT=" + work.string(), "AOSUITE_CASE=" + c.id});
    r.exit_status = run.exit_status;
    r.command_stderr = run.stderr_tail;
    const std::string said = last_line(run.stderr_tail);
    if (run.timed_out) {
      throw std::runtime_error(
          fmt::format("command timed out after {} s and was killed", src.timeout_seconds));
    }
    if (run.signal != 0) {
      const char* name = ::sigabbrev_np(run.signal);
      const char* what = ::sigdescr_np(run.signal);
      throw std::runtime_error(fmt::format("command was killed by SIG{} ({}){}",
                                           name ? std::string(name) : std::to_string(run.signal),
                                           what ? what : "", said.empty() ? "" : ": " + said));
    }
    if (run.exit_status != 0) {
      throw std::runtime_error(fmt::format("command exited with status {}{}", run.exit_status,
                                           said.empty() ? "" : ": " + said));
    }
    from.clear();
    for (const std::string& o : src.outputs) from.push_back(work / o);
  }
  for (std::size_t i = 0; i < c.images.size(); ++i) {
    const std::string& name = c.images[i];
    if (!fs::exists(from[i])) {
      throw std::runtime_error(src.command.empty() ? from[i].string() + ": no such image file"
                                                   : "the command did not write " + src.outputs[i] +
                                                         " (" + from[i].string() + ")");
    }
    if (!src.follow_links)
      check_no_link_out(from[i], staging ? staging->path() : src.dir, kFollowLinks);
    out.bytes[name] = read_regular_file(from[i]);
    if (src.ext == ".png") check_png(out.bytes[name], from[i].string());
    keep_in_report(case_dir / (name + src.ext), out.bytes[name]);
  }
}

std::string bytes_hash(const std::vector<unsigned char>& bytes) {
  return ContentHash().add(std::span<const unsigned char>(bytes)).hex();
}

// The previous run's images, if the report folder still holds exactly the bytes it recorded
// (regular files, not links).
bool reuse_render(const Case& c, const CaseResult& prev, const fs::path& case_dir, CaseResult& r,
                  Rendered& out) {
  for (const std::string& name : kept_images(c)) {
    const fs::path file = case_dir / (name + ext_of(c, name));
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(file, ec)) || !prev.image_hashes.count(name))
      return false;
  }
  for (const std::string& name : kept_images(c)) {
    out.bytes[name] = read_regular_file(case_dir / (name + ext_of(c, name)));
    if (bytes_hash(out.bytes[name]) != prev.image_hashes.at(name)) return false;
  }
  r.image_hashes = prev.image_hashes;
  r.times = prev.times, r.figures = prev.figures;
  r.exit_status = prev.exit_status, r.command_stderr = prev.command_stderr;
  return true;
}

// A case's image as Resemble sees it, 8-bit RGBA, decoded once; empty for a float (linear)
// image, which only the metrics judge.
const RgbaImage& pixels(Rendered& r, const Case& c, const std::string& name,
                        const fs::path& case_dir) {
  RgbaImage& m = r.rgba[name];
  if (!m.empty()) return m;
  const std::vector<unsigned char>& bytes = r.bytes.at(name);
  const std::string ext = ext_of(c, name), file = (case_dir / (name + ext)).string();
  if (ext == ".exr") return m;  // float, whatever the bytes: the metrics (or bytes) judge it
  if (is_png(bytes)) {
    m = decode_png(bytes, file);
  } else if (!is_exr(bytes)) {
    const Picture p = decode_picture(bytes, file, kMaxFileBytes);
    if (!p.is_float || p.floats.srgb) m = canvas_rgba8(p);
  }
  return m;
}

CaseResult skeleton(const Case& c) {
  CaseResult r;
  r.id = c.id, r.tolerance = c.tolerance;
  if (c.source) {
    const ImageSource& src = *c.source;
    r.kind = !src.path.empty() ? "folder" : src.command.empty() ? "files" : "command";
    r.width = c.width, r.height = c.height;
    if (!src.path.empty()) {
      r.source = src.path, r.width = r.height = 0;
    } else if (!src.command.empty()) {
      for (const std::string& a : src.command)
        r.source += (r.source.empty() ? "" : " ") + shell_quote(a);
    } else {
      for (const fs::path& f : src.files) r.source += (r.source.empty() ? "" : " ") + f.string();
    }
    for (const auto& [k, v] : c.values.items()) r.params[k] = v;
    for (const std::string& image : c.images) r.files[image] = c.id + "/" + image + src.ext;
    return r;
  }
  r.kind = std::string(c.kind->name());
  r.width = c.width, r.height = c.height;
  c.made->describe(c, r);
  for (const std::string& image : kept_images(c))
    r.files[image] = c.id + "/" + image + ext_of(c, image);
  return r;
}

// Renders, runs or reads (or reuses) one case into the report folder: the part check and bless
// share. Returns the previous result when the images were reused.
std::optional<CaseResult> prepare(Makers& makers, const std::string& environment, const Case& c,
                                  const RunOptions& o, const Cache& cache, CaseResult& r,
                                  Rendered& images) {
  const fs::path case_dir = o.report_dir / "cases" / c.id;
  r.input_hash = c.source ? image_input_hash(c) : c.made->input_hash(c, environment);
  std::optional<CaseResult> prev;
  if (const auto it = cache.find(c.id); o.reuse && it != cache.end()) prev = it->second;
  const bool undeclared = c.source && !c.source->command.empty() && !c.source->declared;
  if (prev && prev->input_hash == r.input_hash && undeclared) {
    r.not_reused =
        "run again: the case declares no inputs or env, so what its command reads "
        "may have changed";
    prev.reset();
  }
  if (prev && prev->input_hash == r.input_hash && reuse_render(c, *prev, case_dir, r, images)) {
    return prev;
  }
  images = {};
  if (c.source) {
    produce_images(c, case_dir, r, images);
  } else {
    makers.get(c.kind).make(c, case_dir, r, images);
  }
  r.image_hashes.clear();
  for (const std::string& name : kept_images(c))
    r.image_hashes[name] = bytes_hash(images.bytes.at(name));
  return std::nullopt;
}

// Folder mode reads, writes and removes under --expected by relative path: never through a link
// there (a linked file or folder leads out of --expected). Throws naming the link.
void refuse_links_below(const fs::path& root, const fs::path& file) {
  fs::path at = root;
  for (const fs::path& part : file.lexically_relative(root)) {
    at /= part;
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(at, ec))) {
      throw std::runtime_error(at.string() + ": a symbolic link; nothing is written through it");
    }
  }
}

// Where a case's image is accepted: folder mode's expected file, else its golden (variant).
fs::path bless_target(const Suite& suite, const Case& c, const std::string& image,
                      const std::string& platform, const std::string& tag) {
  if (c.source && !c.source->golden_file.empty()) return c.source->golden_file;
  return golden_path(suite.goldens / c.id, image, ext_of(c, image), platform, tag);
}

// The goldens accepted for one image: folder mode's one expected file, else the goldens folder.
std::vector<fs::path> goldens_of(const Suite& suite, const Case& c, const std::string& image,
                                 const std::string& platform) {
  if (c.source && !c.source->golden_file.empty()) {
    refuse_links_below(suite.goldens, c.source->golden_file);
    std::error_code ec;
    if (fs::exists(fs::symlink_status(c.source->golden_file, ec))) return {c.source->golden_file};
    return {};
  }
  std::vector<fs::path> found =
      accepted_goldens(suite.goldens / c.id, image, ext_of(c, image), platform);
  if (!suite.follow_links) {
    for (const fs::path& g : found) check_no_link_out(g, suite.goldens, kFollowLinks);
  }
  return found;
}

// foreground_only's pixels: the kept mask's white ones.
std::optional<Counted> foreground(const Case& c, Rendered& images, const fs::path& case_dir) {
  if (!c.tolerance.foreground_only) return std::nullopt;
  const RgbaImage& mask = pixels(images, c, "foreground", case_dir);
  Counted out(std::size_t(mask.width()) * std::size_t(mask.height()));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = mask.data()[4 * i] != 0;
  return out;
}

void judge_case(const Suite& suite, const Case& c, const std::string& platform, const RunOptions& o,
                const std::optional<CaseResult>& prev, CaseResult& r, Rendered& images) {
  const fs::path case_dir = o.report_dir / "cases" / c.id;
  std::vector<std::vector<ReadGolden>> goldens;
  for (const std::string& image : c.images)
    goldens.push_back(read_goldens(goldens_of(suite, c, image, platform)));
  r.judge_hash = judge_hash(c, r.input_hash, goldens);
  if (prev && prev->judge_hash == r.judge_hash && prev->status != Status::kError) {
    const double seconds = r.seconds;
    r = *prev;
    r.reused = true, r.seconds = seconds, r.attempts = 1;
    if (r.status == Status::kFlaky) r.status = Status::kPass;  // this run passed at once
    return;
  }
  r.status = Status::kPass;
  const std::optional<Counted> counted = foreground(c, images, case_dir);
  for (std::size_t i = 0; i < c.images.size(); ++i) {
    const std::string& name = c.images[i];
    const std::string ext = ext_of(c, name);
    ImageVerdict v = judge(name, images.bytes.at(name), goldens[i], c.tolerance, true,
                           counted ? &*counted : nullptr);
    if (v.status == Status::kNew)
      v.message += " at " + printable(bless_target(suite, c, name, "", "").string());
    const bool show = v.status == Status::kFail || v.status == Status::kWarn || o.diff_all;
    if (!v.diff.empty() && show) {
      write_png_rgba8(case_dir / ("diff_" + name + ".png"), v.diff);
      r.files["diff:" + name] = c.id + "/diff_" + name + ".png";
    }
    if (!v.heatmap.empty() && show) {
      write_png_rgba8(case_dir / ("heat_" + name + ".png"), v.heatmap);
      r.files["heat:" + name] = c.id + "/heat_" + name + ".png";
    }
    if (show && !v.ignored.empty()) {  // what the tolerance ignored, drawn over the diff
      write_png_rgba8(case_dir / ("ignored_" + name + ".png"),
                      ignored_overlay(v.ignored, v.diff.width(), v.diff.height()));
      r.files["ignored:" + name] = c.id + "/ignored_" + name + ".png";
    }
    if (!c.tolerance.regions.empty() && !v.golden.empty()) {
      const fs::path map = region_map(v.golden, name);
      if (fs::is_regular_file(map)) {
        keep_in_report(case_dir / ("regions_" + name + ".png"), read_regular_file(map));
        r.files["regions:" + name] = c.id + "/regions_" + name + ".png";
      }
    }
    if (!v.identical && !v.golden.empty() && v.status != Status::kError) {
      // A copy written under a temporary name and renamed: never a truncated golden image in
      // the report, even on a full disk.
      // The bytes judged, not the file as it is now.
      const auto judged = std::ranges::find(goldens[i], v.golden, &ReadGolden::file);
      keep_in_report(case_dir / ("golden_" + name + ext),
                     judged != goldens[i].end() ? judged->bytes : read_regular_file(v.golden));
      r.files["golden:" + name] = c.id + "/golden_" + name + ext;
    } else if (v.identical) {
      r.files["golden:" + name] = c.id + "/" + name + ext;
    }
    if (r.message.empty() && v.status != Status::kPass) r.message = name + ": " + v.message;
    r.status = worst(r.status, v.status);
    v.diff = {}, v.heatmap = {};
    r.images.push_back(std::move(v));
  }
}

// Folder mode: an image only in the expected folder.
void judge_deleted(const Case& c, const RunOptions& o, CaseResult& r) {
  const fs::path case_dir = o.report_dir / "cases" / c.id;
  fs::create_directories(case_dir);
  r.files.clear();
  keep_in_report(case_dir / ("golden_image" + c.source->ext),
                 read_regular_file(c.source->golden_file));
  r.files["golden:image"] = c.id + "/golden_image" + c.source->ext;
  r.status = Status::kFail, r.deleted = true;
  r.message = "deleted: only in the expected folder";
  ImageVerdict v;
  v.image = "image", v.status = Status::kFail, v.golden = c.source->golden_file;
  v.mismatch_percent = 100, v.mismatch_text = "100.00", v.message = r.message;
  r.images.push_back(std::move(v));
}

// Runs `work(makers, case, result)` over the cases on `jobs` threads, each with its own makers
// (made when a case first needs one); `first` is the main thread's, reused by worker 0.
template <typename Work>
std::vector<CaseResult> for_each_case(const std::vector<const Case*>& cases, const RunOptions& o,
                                      Makers first, Work work) {
  std::vector<CaseResult> results(cases.size());
  std::atomic<std::size_t> next{0};
  std::atomic<int> done{0};
  std::mutex report;
  auto worker = [&](Makers makers) {
    for (std::size_t i; (i = next++) < cases.size();) {
      const auto t0 = std::chrono::steady_clock::now();
      CaseResult& r = results[i];
      r = skeleton(*cases[i]);
      try {
        work(makers, *cases[i], r);
      } catch (const std::exception& e) {
        r.status = Status::kError;
        r.message = e.what();
      }
      r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const std::lock_guard lock(report);
      if (o.progress) o.progress(r, ++done, static_cast<int>(cases.size()));
    }
  };
  const int jobs = std::max(1, std::min<int>(o.jobs, static_cast<int>(cases.size())));
  std::vector<std::thread> threads;
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker, Makers{});
  worker(std::move(first));
  for (std::thread& t : threads) t.join();
  return results;
}

std::string list_command(const Suite& suite) {
  return program_command() + " check " +
         (suite.check_args.empty() ? shell_quote(suite.file.string()) : suite.check_args) +
         " --list";
}

// The selected cases; an empty selection is an error, found before anything is written: a run
// that judged nothing is never green and must not replace the last report.
std::vector<const Case*> select_some(const Suite& suite, const Selection& s) {
  std::vector<const Case*> cases = select(suite, s);
  if (!cases.empty()) return cases;
  std::string why =
      s.filter.empty() ? std::string("the suite") : "--filter " + shell_quote(s.filter);
  if (s.shard_count > 1) why += fmt::format(" with shard {}/{}", s.shard_index, s.shard_count);
  throw std::invalid_argument(fmt::format(
      "{}: {} selects none of its {} cases; nothing was run (ids: {})",
      printable(suite.file.string()), printable(why), suite.cases.size(), list_command(suite)));
}

RunResults start(const Suite& suite, const RunOptions& o, const std::vector<const Case*>& cases,
                 bool may_render, Makers& first) {
  RunResults run;
  run.suite = suite.name, run.suite_file = absolute_path(suite.file);
  run.goldens = absolute_path(suite.goldens);
  run.expected_folder = suite.expected.empty() ? "" : absolute_path(suite.expected);
  run.bless_prefix = bless_prefix(suite);
  run.approve_prefix = run.bless_prefix + " --from-report --report " +
                       shell_quote(o.report_dir.lexically_normal().string());
  // The first case of a registered kind makes its maker here: what it says of the machine
  // (the GL implementation) is in every input hash, and names the platform's goldens.
  const auto made = std::find_if(cases.begin(), cases.end(), [](const Case* c) { return c->kind; });
  if (may_render && made != cases.end()) {
    Environment env;
    first.by_kind[(*made)->kind] = (*made)->kind->maker(&env);
    run.environment = env.description, run.platform = env.platform;
  }
  if (const char* p = std::getenv("AOSUITE_PLATFORM"); p && *p) run.platform = p;
  if (!o.platform.empty()) run.platform = o.platform;
  if (!run.platform.empty() && !valid_name(run.platform)) {
    throw std::invalid_argument("platform '" + printable(run.platform) +
                                "' must be letters, digits, - _ . (it names a folder)");
  }
  if (o.selection.shard_count > 1) {
    run.shard = fmt::format("{}/{}", o.selection.shard_index, o.selection.shard_count);
  }
  fs::create_directories(o.report_dir / "cases");
  // The last run's page goes before this run writes anything: should its page then fail to be
  // written (a full disk), the folder shows no page rather than one older than its results.
  std::error_code ec;
  fs::remove(o.report_dir / "index.html", ec);
  return run;
}

// One attempt at a case: images, then the verdict.
void check_once(const Suite& suite, const std::string& environment, const std::string& platform,
                const RunOptions& o, const Cache& cache, Makers& makers, const Case& c,
                CaseResult& r) {
  if (c.source && c.source->deleted) {
    r.input_hash = r.judge_hash = "";
    judge_deleted(c, o, r);
    return;
  }
  Rendered images;
  const auto prev = prepare(makers, environment, c, o, cache, r, images);
  judge_case(suite, c, platform, o, prev, r, images);
}

}  // namespace

RunResults check(const Suite& suite, const RunOptions& o) {
  const std::vector<const Case*> cases = select_some(suite, o.selection);
  Makers first;
  RunResults run = start(suite, o, cases, true, first);
  const std::string environment = run.environment, platform = run.platform;
  const Cache cache = load_cache(o.report_dir);
  RunOptions again = o;
  again.reuse = false;
  run.cases =
      for_each_case(cases, o, std::move(first), [&](Makers& makers, const Case& c, CaseResult& r) {
        auto attempt = [&](const RunOptions& opts, CaseResult& into) {
          try {
            check_once(suite, environment, platform, opts, cache, makers, c, into);
          } catch (const std::exception& e) {
            into.status = Status::kError;
            into.message = e.what();
          }
        };
        attempt(o, r);
        const CaseResult first_try = r;
        for (int k = 1; k <= o.retries && (r.status == Status::kFail || r.status == Status::kError);
             ++k) {
          r = skeleton(c);
          attempt(again, r);
          r.attempts = k + 1;
          if (r.status == Status::kPass || r.status == Status::kWarn) {
            r.status = Status::kFlaky;
            r.message =
                fmt::format("failed, then passed on attempt {}: {}", k + 1, first_try.message);
          }
        }
        if (awaits_approval(r.status)) {
          r.bless_command = bless_command(bless_prefix(suite), {c.id});
        }
      });
  write_results(o.report_dir, run);
  save_cache(o.report_dir, cache, run.cases);
  return run;
}

namespace {

void write_case_goldens(const Suite& suite, const Case& c, const std::string& platform,
                        const std::string& tag, const Rendered& images, CaseResult& r) {
  const fs::path dir = c.source && !c.source->golden_file.empty()
                           ? c.source->golden_file.parent_path()
                           : suite.goldens / c.id;
  std::vector<GoldenWrite> writes;
  std::string written;
  std::vector<std::vector<unsigned char>> blank_maps;
  blank_maps.reserve(c.images.size());
  for (const std::string& image : c.images) {
    const fs::path target = bless_target(suite, c, image, platform, tag);
    writes.emplace_back(target, images.bytes.at(image));
    written += (written.empty() ? "" : ", ") + writes.back().first.string();
    // Regions need a map beside the golden: a black one (every pixel unpainted) to paint,
    // never over one that exists.
    const fs::path map = region_map(target, image);
    if (!c.tolerance.regions.empty() && !fs::exists(map)) {
      const ImageSize size = decode_picture(images.bytes.at(image), target.string()).size();
      RgbaImage black(size.width, size.height);
      for (std::size_t i = 3; i < black.view().bytes(); i += 4) black.data()[i] = 255;
      blank_maps.push_back(encode_png_rgba8(black, 6));
      writes.emplace_back(map, blank_maps.back());
      written += ", " + map.string();
    }
  }
  remove_stale_temporaries(dir);
  try {
    // Folder mode's one expected file is replaced by one rename; a suite case's folder whole.
    if (c.source && !c.source->golden_file.empty()) {
      refuse_links_below(suite.goldens, c.source->golden_file);
      replace_goldens(writes);
    } else {
      replace_case_goldens(dir, writes);
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("goldens not written: ") + e.what());
  }
  r.status = Status::kPass;
  r.message = "wrote " + written;
}

// Folder mode: accepting a deleted image removes the expected file.
void accept_deletion(const Suite& suite, const Case& c, CaseResult& r) {
  refuse_links_below(suite.goldens, c.source->golden_file);
  std::error_code ec;
  if (!fs::remove(c.source->golden_file, ec) && ec) {
    throw std::runtime_error(c.source->golden_file.string() + ": cannot remove: " + ec.message());
  }
  r.status = Status::kPass;
  r.message = "removed " + c.source->golden_file.string();
}

}  // namespace

RunResults bless(const Suite& suite, const BlessOptions& b) {
  if (!b.tag.empty() && !valid_name(b.tag)) {
    throw std::invalid_argument(
        "--variant '" + printable(b.tag) +
        "' must be letters, digits, - _ . and not start with '.' (it names a file)");
  }
  const bool from_report = b.from_report || b.failed;
  std::vector<const Case*> cases;
  std::map<std::string, CaseResult> reported;
  std::string report_platform;  // the platform the report's images were made on
  if (from_report) {
    const RunResults last = read_results(b.run.report_dir);
    report_platform = last.platform;
    if (last.suite != suite.name) {
      throw std::invalid_argument(printable(
          fmt::format("{}: a report of suite '{}', not '{}'",
                      (b.run.report_dir / "results.json").string(), last.suite, suite.name)));
    }
    for (const CaseResult& c : last.cases) reported[c.id] = c;
    if (b.failed) {
      for (const Case* c : select(suite, b.run.selection)) {
        const auto it = reported.find(c->id);
        if (it != reported.end() && awaits_approval(it->second.status)) {
          cases.push_back(c);
        }
      }
      if (cases.empty()) {
        RunResults none;
        none.suite = suite.name, none.suite_file = absolute_path(suite.file);
        none.expected_folder = suite.expected.empty() ? "" : absolute_path(suite.expected);
        return none;
      }
    }
  }
  if (cases.empty()) cases = select_some(suite, b.run.selection);
  Makers first;
  RunResults run = start(suite, b.run, cases, !from_report, first);
  if (from_report && run.platform.empty()) run.platform = report_platform;
  if (b.platform && run.platform.empty()) {
    throw std::invalid_argument(
        "--platform: no platform key (these cases render no scene): set AOSUITE_PLATFORM");
  }
  const std::string environment = run.environment;
  const std::string platform = b.platform ? run.platform : std::string();
  const std::string judge_platform = run.platform;
  const Cache cache = from_report ? Cache() : load_cache(b.run.report_dir);
  run.cases = for_each_case(
      cases, b.run, std::move(first), [&](Makers& makers, const Case& c, CaseResult& r) {
        const bool deleted = c.source && c.source->deleted;
        Rendered images;
        if (from_report) {
          const auto it = reported.find(c.id);
          if (it == reported.end()) {
            throw std::runtime_error("not in the report " + b.run.report_dir.string() +
                                     " (check it first); its goldens are untouched");
          }
          const Status was = it->second.status;
          if ((was == Status::kPass || was == Status::kFlaky) && !b.force) {
            r.status = Status::kPass, r.kept = true;
            r.message = "passed in the report; goldens kept (--force rewrites them)";
            return;
          }
          if (was == Status::kError) {
            throw std::runtime_error("could not be judged in the report (" + it->second.message +
                                     "); its goldens are untouched");
          }
          if (!deleted) {
            for (const std::string& image : c.images) {
              const fs::path f = b.run.report_dir / "cases" / c.id / (image + ext_of(c, image));
              try {
                // What was reviewed is what is approved: the file must be the one the report's
                // results.json recorded (a later or killed run may have replaced it), and a
                // file, not a link to anything outside the report.
                std::error_code ec;
                if (!fs::is_regular_file(fs::symlink_status(f, ec)))
                  throw FileError(f.string() + ": not a regular file");
                images.bytes[image] = read_regular_file(f);
                const auto recorded = it->second.image_hashes.find(image);
                if (recorded == it->second.image_hashes.end() ||
                    recorded->second != bytes_hash(images.bytes[image])) {
                  throw FileError(
                      f.string() +
                      ": not the image the report judged (replaced since; check again)");
                }
                if (ext_of(c, image) == ".png") check_png(images.bytes[image], f.string());
              } catch (const std::exception& e) {
                throw std::runtime_error(std::string("the report's image is unusable: ") +
                                         e.what() + "; its goldens are untouched");
              }
            }
          }
        } else if (!deleted) {
          std::optional<CaseResult> prev;
          try {
            prev = prepare(makers, environment, c, b.run, cache, r, images);
          } catch (const std::exception& e) {
            throw std::runtime_error(std::string("could not be rendered: ") + e.what() +
                                     "; its goldens are untouched");
          }
          // A passing case is left alone: bless never rewrites its goldens unless asked (--force),
          // but it does write a platform golden or variant that does not exist yet.
          bool targets_exist = true;
          for (const std::string& image : c.images) {
            targets_exist =
                targets_exist && fs::exists(bless_target(suite, c, image, platform, b.tag));
          }
          if (!b.force && targets_exist) {
            CaseResult verdict = r;
            try {
              judge_case(suite, c, judge_platform, b.run, std::nullopt, verdict, images);
            } catch (const std::exception&) {
              verdict.status = Status::kError;  // whatever is wrong there, bless replaces it
            }
            if (verdict.status == Status::kPass) {
              r.status = Status::kPass, r.kept = true;
              r.message = "passes; goldens kept (--force rewrites them)";
              return;
            }
          }
        }
        if (deleted) {
          accept_deletion(suite, c, r);
        } else {
          write_case_goldens(suite, c, platform, b.tag, images, r);
        }
      });
  return run;
}

}  // namespace aosuite::harness

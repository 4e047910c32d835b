#include "harness/runner.hpp"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "compare/opencv.hpp"
#include "harness/case_hash.hpp"
#include "harness/escape.hpp"
#include "harness/goldens.hpp"
#include "renderer/params.hpp"
#include "renderer/renderer.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;

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
  std::string out = "aosuite bless " + shell_quote(suite.file.string());
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

// A case's three images as PNG bytes and pixels, fresh or reused from the report folder.
struct Rendered {
  std::map<std::string, std::vector<unsigned char>> png;
  std::map<std::string, cv::Mat> rgba;
};

std::optional<CaseResult> previous(const fs::path& case_dir) {
  std::ifstream in(case_dir / "case.json");
  if (!in) return std::nullopt;
  try {
    return case_from_json(nlohmann::json::parse(in));
  } catch (const std::exception&) {
    return std::nullopt;  // a damaged cache entry only costs a re-render
  }
}

double raw_mismatch(const cv::Mat& a, const cv::Mat& b, resemble::Mode mode) {
  resemble::Options o;
  o.modes = {mode};
  return resemble::compare(a, b, o).raw_mismatch_percentage;
}

// Renders the case into `r`, writing its images to `case_dir`; fills times and the AO effect.
void render_case(rd::Renderer& renderer, const Case& c, const fs::path& case_dir, CaseResult& r,
                 Rendered& out) {
  rd::RenderSettings s;
  s.width = c.width, s.height = c.height, s.technique = c.technique, s.params = c.params;
  s.outputs = {.no_ao = true, .with_ao = true, .ao_only = true, .ao_float = false};
  rd::Images img = renderer.render(*c.scene, rd::find_view(*c.scene, c.view), s);
  out.rgba = {{"no_ao", img.no_ao}, {"with_ao", img.with_ao}, {"ao_only", img.ao_only}};
  fs::create_directories(case_dir);
  for (const auto& [name, mat] : out.rgba) {
    out.png[name] = encode_png_rgba8(mat, 6);
    write_file_atomic(case_dir / (name + ".png"), out.png[name]);
  }
  r.times = img.times;
  r.ao_effect_less = raw_mismatch(img.no_ao, img.with_ao, resemble::Mode::kLess);
  r.ao_effect_nothing = raw_mismatch(img.no_ao, img.with_ao, resemble::Mode::kNothing);
}

bool reuse_render(const CaseResult& prev, const fs::path& case_dir, CaseResult& r, Rendered& out) {
  for (const char* name : kImageNames) {
    if (!fs::is_regular_file(case_dir / (std::string(name) + ".png"))) return false;
  }
  for (const char* name : kImageNames) {
    out.png[name] = read_file(case_dir / (std::string(name) + ".png"));
  }
  r.times = prev.times;
  r.ao_effect_less = prev.ao_effect_less, r.ao_effect_nothing = prev.ao_effect_nothing;
  return true;
}

const cv::Mat& pixels(Rendered& r, const std::string& name, const fs::path& case_dir) {
  cv::Mat& m = r.rgba[name];
  if (m.empty()) m = decode_png_rgba8(r.png.at(name), (case_dir / (name + ".png")).string());
  return m;
}

Status worst(Status a, Status b) {
  auto rank = [](Status s) {
    return s == Status::kError ? 3 : s == Status::kFail ? 2 : s == Status::kNew ? 1 : 0;
  };
  return rank(a) >= rank(b) ? a : b;
}

CaseResult skeleton(const Case& c) {
  CaseResult r;
  r.id = c.id, r.scene = c.scene->name, r.view = c.view;
  r.technique = std::string(rd::technique_name(c.technique));
  r.width = c.width, r.height = c.height, r.tolerance = c.tolerance;
  for (const rd::ParamSpec& spec : rd::param_specs()) {
    if (rd::applies(spec, c.technique))
      r.params[std::string(spec.key)] = rd::param_text(spec, c.params);
  }
  r.files = {{"no_ao", c.id + "/no_ao.png"},
             {"with_ao", c.id + "/with_ao.png"},
             {"ao_only", c.id + "/ao_only.png"}};
  return r;
}

// Renders (or reuses) one case into the report folder: the part check and bless share.
// Returns the previous result when the render was reused.
std::optional<CaseResult> prepare(rd::Renderer& renderer, const std::string& gl, const Case& c,
                                  const RunOptions& o, CaseResult& r, Rendered& images) {
  const fs::path case_dir = o.report_dir / "cases" / c.id;
  r.input_hash = input_hash(c, gl);
  std::optional<CaseResult> prev = o.reuse ? previous(case_dir) : std::nullopt;
  if (prev && prev->input_hash == r.input_hash && reuse_render(*prev, case_dir, r, images)) {
    return prev;
  }
  render_case(renderer, c, case_dir, r, images);
  return std::nullopt;
}

void judge_case(const Suite& suite, const Case& c, const std::string& platform, const RunOptions& o,
                const std::optional<CaseResult>& prev, CaseResult& r, Rendered& images) {
  const fs::path case_dir = o.report_dir / "cases" / c.id;
  const fs::path golden_dir = suite.goldens / c.id;
  std::vector<std::vector<fs::path>> goldens;
  for (const std::string& image : c.images) {
    goldens.push_back(accepted_goldens(golden_dir, image, platform));
  }
  r.judge_hash = judge_hash(c, r.input_hash, goldens);
  if (prev && prev->judge_hash == r.judge_hash) {
    const double seconds = r.seconds;
    r = *prev;
    r.reused = true, r.seconds = seconds;
    return;
  }
  r.status = Status::kPass;
  for (std::size_t i = 0; i < c.images.size(); ++i) {
    const std::string& name = c.images[i];
    ImageVerdict v = judge(name, images.png.at(name), pixels(images, name, case_dir), goldens[i],
                           c.tolerance, true);
    const bool show = v.status == Status::kFail || o.diff_all;
    if (!v.diff.empty() && show) {
      write_png_rgba8(case_dir / ("diff_" + name + ".png"), v.diff);
      r.files["diff:" + name] = c.id + "/diff_" + name + ".png";
    }
    if (!v.identical && !v.golden.empty() && v.status != Status::kError) {
      // A copy written under a temporary name and renamed: never a truncated golden image in
      // the report, even on a full disk.
      write_file_atomic(case_dir / ("golden_" + name + ".png"), read_file(v.golden));
      r.files["golden:" + name] = c.id + "/golden_" + name + ".png";
    } else if (v.identical) {
      r.files["golden:" + name] = c.id + "/" + name + ".png";
    }
    if (r.message.empty() && v.status != Status::kPass) r.message = name + ": " + v.message;
    r.status = worst(r.status, v.status);
    v.diff = {};
    r.images.push_back(std::move(v));
  }
  if (r.status != Status::kPass && r.status != Status::kError) {
    r.bless_command = bless_command(bless_prefix(suite), {c.id});
  }
}

void save_case(const fs::path& report_dir, const CaseResult& r) {
  const std::string text = to_json(r).dump(1) + "\n";
  write_file_atomic(report_dir / "cases" / r.id / "case.json",
                    {reinterpret_cast<const unsigned char*>(text.data()), text.size()});
}

// Runs `work(renderer, case, result)` over the cases on `jobs` threads, each with its own GL
// context; `first` is the main thread's renderer, reused by worker 0.
template <typename Work>
std::vector<CaseResult> for_each_case(const std::vector<const Case*>& cases, const RunOptions& o,
                                      std::unique_ptr<rd::Renderer> first, Work work) {
  std::vector<CaseResult> results(cases.size());
  std::atomic<std::size_t> next{0};
  std::atomic<int> done{0};
  std::mutex report;
  auto worker = [&](std::unique_ptr<rd::Renderer> renderer) {
    for (std::size_t i; (i = next++) < cases.size();) {
      const auto t0 = std::chrono::steady_clock::now();
      CaseResult& r = results[i];
      r = skeleton(*cases[i]);
      try {
        if (!renderer) renderer = std::make_unique<rd::Renderer>();
        work(*renderer, *cases[i], r);
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
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker, nullptr);
  worker(std::move(first));
  for (std::thread& t : threads) t.join();
  return results;
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
      "{}: {} selects none of its {} cases; nothing was run (ids: aosuite check {} --list)",
      printable(suite.file.string()), printable(why), suite.cases.size(),
      shell_quote(suite.file.string())));
}

RunResults start(const Suite& suite, const RunOptions& o, std::unique_ptr<rd::Renderer>& first) {
  first = std::make_unique<rd::Renderer>();
  RunResults run;
  run.suite = suite.name, run.suite_file = suite.file.string();
  run.bless_prefix = bless_prefix(suite);
  // The backend and device after the driver's own three fields: the report names them, and
  // platform_key reads the renderer field alone, so goldens match on EGL and OSMesa alike.
  run.gl = first->gl_description() + " | " + first->gl_source();
  run.platform = platform_key(run.gl);
  if (o.selection.shard_count > 1) {
    run.shard = fmt::format("{}/{}", o.selection.shard_index, o.selection.shard_count);
  }
  fs::create_directories(o.report_dir / "cases");
  return run;
}

}  // namespace

RunResults check(const Suite& suite, const RunOptions& o) {
  const std::vector<const Case*> cases = select_some(suite, o.selection);
  std::unique_ptr<rd::Renderer> first;
  RunResults run = start(suite, o, first);
  const std::string gl = run.gl, platform = run.platform;
  run.cases = for_each_case(cases, o, std::move(first),
                            [&](rd::Renderer& renderer, const Case& c, CaseResult& r) {
                              Rendered images;
                              const auto prev = prepare(renderer, gl, c, o, r, images);
                              judge_case(suite, c, platform, o, prev, r, images);
                              save_case(o.report_dir, r);
                            });
  write_results(o.report_dir, run);
  return run;
}

RunResults bless(const Suite& suite, const BlessOptions& b) {
  if (!b.tag.empty() && !valid_name(b.tag)) {
    throw std::invalid_argument(
        "--variant '" + printable(b.tag) +
        "' must be letters, digits, - _ . and not start with '.' (it names a file)");
  }
  const std::vector<const Case*> cases = select_some(suite, b.run.selection);
  std::unique_ptr<rd::Renderer> first;
  RunResults run = start(suite, b.run, first);
  const std::string gl = run.gl, platform = b.platform ? run.platform : std::string();
  run.cases = for_each_case(
      cases, b.run, std::move(first), [&](rd::Renderer& renderer, const Case& c, CaseResult& r) {
        Rendered images;
        try {
          prepare(renderer, gl, c, b.run, r, images);
        } catch (const std::exception& e) {
          throw std::runtime_error(std::string("could not be rendered: ") + e.what() +
                                   "; its goldens are untouched");
        }
        const fs::path case_dir = suite.goldens / c.id;
        std::vector<GoldenWrite> writes;
        std::string written;
        for (const std::string& image : c.images) {
          writes.emplace_back(golden_path(case_dir, image, platform, b.tag), images.png.at(image));
          written += (written.empty() ? "" : ", ") + writes.back().first.string();
        }
        remove_stale_temporaries(case_dir);
        try {
          replace_goldens(writes);
        } catch (const std::exception& e) {
          throw std::runtime_error(std::string("goldens not written: ") + e.what());
        }
        r.status = Status::kPass;
        r.message = "wrote " + written;
      });
  return run;
}

}  // namespace aosuite::harness

#include "harness/case_images.hpp"

#include <fmt/format.h>
#include <stdlib.h>  // mkdtemp
#include <string.h>  // sigabbrev_np, sigdescr_np

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "common/file_io.hpp"
#include "harness/case_hash.hpp"
#include "harness/command.hpp"
#include "harness/escape.hpp"
#include "image/image_file.hpp"
#include "image/image_io.hpp"

namespace aosuite::harness {

namespace fs = std::filesystem;

std::string ext_of(const Case& c, std::string_view image) {
  return c.source ? c.source->exts.at(std::string(image)) : c.made->ext(image);
}

std::vector<std::string> kept_images(const Case& c) {
  return c.source ? c.images : c.made->kept_images(c);
}

namespace {

bool is_shell(const std::string& program) {
  const std::string base = fs::path(program).filename().string();
  return base == "sh" || base == "bash" || base == "dash" || base == "zsh" || base == "ksh";
}

std::string last_line(std::string_view text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.remove_suffix(1);
  const std::size_t nl = text.rfind('\n');
  return std::string(nl == std::string_view::npos ? text : text.substr(nl + 1));
}

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
void produce_images(const Case& c, const fs::path& case_dir, CaseResult& r, CaseImages& out) {
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
    const std::string& ext = src.exts.at(name);
    if (ext == ".png") check_png(out.bytes[name], from[i].string());
    keep_in_report(case_dir / (name + ext), out.bytes[name]);
  }
}

// The previous run's images into `out`, if the report folder still holds exactly the bytes
// `prev` recorded (regular files, not links); false, and nothing to trust in `out`, if not.
bool reuse_images(const Case& c, const CaseResult& prev, const fs::path& case_dir, CaseResult& r,
                  CaseImages& out) {
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
  r.times = prev.times, r.figures = prev.figures, r.pass_hashes = prev.pass_hashes;
  r.exit_status = prev.exit_status, r.command_stderr = prev.command_stderr;
  return true;
}

}  // namespace

const RgbaImage& decoded_pixels(CaseImages& r, const Case& c, const std::string& name,
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

CaseResult result_skeleton(const Case& c) {
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
    for (const std::string& image : c.images)
      r.files[image] = c.id + "/" + image + src.exts.at(image);
    return r;
  }
  r.kind = std::string(c.kind->name());
  r.width = c.width, r.height = c.height;
  c.made->describe(c, r);
  for (const std::string& image : kept_images(c))
    r.files[image] = c.id + "/" + image + ext_of(c, image);
  return r;
}

std::optional<CaseResult> prepare_images(Makers& makers, const std::string& environment,
                                         const Case& c, const RunOptions& o, const Cache& cache,
                                         CaseResult& r, CaseImages& images) {
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
  if (prev && prev->input_hash == r.input_hash && reuse_images(c, *prev, case_dir, r, images)) {
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

}  // namespace aosuite::harness

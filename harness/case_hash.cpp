#include "harness/case_hash.hpp"

#include <unistd.h>

#include <cstdlib>
#include <map>
#include <span>
#include <sstream>

#include "common/content_hash.hpp"

namespace aosuite::harness {
namespace fs = std::filesystem;

using Hasher = ContentHash;

namespace {

// The file execvp would run for `program`: a path as given (relative ones from the suite's
// folder, where the suite's author wrote them), else the first executable of that name on PATH;
// empty when there is none.
fs::path resolve_program(const std::string& program, const fs::path& suite_dir) {
  std::error_code ec;
  if (program.find('/') != std::string::npos) {
    const fs::path p(program);
    return p.is_absolute() || !fs::exists(suite_dir / p, ec) ? p : suite_dir / p;
  }
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / program;
    if (fs::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return {};
}

// What a command case runs: the program's bytes (found on PATH as execvp finds it), and the
// bytes of every argument that names an existing file (after its placeholders; {out}, the
// case's own output folder, excepted), so an edited script or a rebuilt binary is run again
// whether or not the suite lists it in `inputs`.
void add_command(Hasher& h, const Case& c) {
  const ImageSource& src = *c.source;
  // Arguments under {out} name what the command writes: marked by a byte no path holds.
  static const std::string kOut(1, '\x01');
  std::map<std::string, std::string> values = command_placeholders(c);
  values.insert_or_assign("out", kOut);
  std::error_code ec;
  for (std::size_t i = 0; i < src.command.size(); ++i) {
    const std::string arg = expand_placeholders(src.command[i], values, false);
    h.add(src.command[i]);
    if (arg.find(kOut) != std::string::npos) continue;
    const fs::path file = i == 0 ? resolve_program(arg, src.dir) : fs::path(arg);
    const fs::path found = file.is_absolute() || file.empty() ? file : src.dir / file;
    if (!found.empty() && fs::is_regular_file(found, ec)) h.add(found.string()).add_file(found);
  }
  for (const std::string& name : src.env) {
    const char* value = std::getenv(name.c_str());
    h.add(name).add(value != nullptr).add(std::string_view(value ? value : ""));
  }
}

}  // namespace

std::string image_input_hash(const Case& c) {
  const ImageSource& src = *c.source;
  Hasher h;
  h.add(std::string_view("image case 2")).add(c.id).add(c.width).add(c.height);
  h.add(c.values.dump());
  h.add(src.command.size());
  add_command(h, c);
  for (const std::string& out : src.outputs) h.add(out);
  for (const fs::path& in : src.inputs) h.add(in.string()).add_file(in);
  for (const fs::path& f : src.files) h.add(f.string()).add_file(f);
  return h.hex();
}

std::string judge_hash(const Case& c, const std::string& input,
                       const std::vector<std::vector<ReadGolden>>& goldens) {
  Hasher h;
  h.add(input);
  const Tolerance& t = c.tolerance;
  h.add(t.resemble)
      .add(t.foreground_only)
      .add(t.mode)
      .add(t.max_mismatch_percent)
      .add(t.max_channel_delta)
      .add(t.min_channel_delta)
      .add(t.min_differing_pixels)
      .add(t.max_differing_pixels)
      .add(t.max_mean_shift)
      .add(t.max_mean_delta)
      .add(t.shift_radius)
      .add(t.allow_kind_change);
  const auto add_gates = [&](const std::vector<metric::Gates>& gates) {
    h.add(gates.size());
    for (const metric::Gates& g : gates) {
      h.add(std::string(g.metric->name)).add(g.allow_nonfinite).add(g.limits.size());
      for (const metric::Limit& l : g.limits) h.add(l.stat).add(l.is_max).add(l.limit);
    }
  };
  add_gates(t.gates);
  add_gates(t.float_gates);
  h.add(t.warn.max_mismatch_percent).add(t.warn.max_channel_delta).add(t.warn.max_differing_pixels);
  add_gates(t.warn.gates);
  for (const Region& r : t.regions) {
    h.add(r.name).add(r.color);
    add_gates(r.gates);
  }
  for (const resemble::Box& b : t.ignore) h.add(b.left).add(b.top).add(b.right).add(b.bottom);
  if (!t.mask.empty()) h.add_file(t.mask);
  for (std::size_t i = 0; i < goldens.size(); ++i) {
    h.add(c.images[i]).add(goldens[i].size());
    for (const ReadGolden& read : goldens[i]) {
      const fs::path& g = read.file;
      h.add(g.parent_path().filename().string()).add(g.filename().string());
      h.add(std::span<const unsigned char>(read.bytes)).add(read.error);
      // The region map beside it decides which pixels each region's gates see.
      const fs::path map = region_map(g, c.images[i]);
      if (!t.regions.empty() && fs::is_regular_file(map)) h.add_file(map);
    }
  }
  return h.hex();
}

}  // namespace aosuite::harness

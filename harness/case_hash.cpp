#include "harness/case_hash.hpp"

#include <span>

#include "common/content_hash.hpp"

namespace aosuite::harness {
namespace fs = std::filesystem;

using Hasher = ContentHash;

std::string image_input_hash(const Case& c) {
  const ImageSource& src = *c.source;
  Hasher h;
  h.add(std::string_view("image case 1")).add(c.id).add(c.width).add(c.height);
  h.add(c.values.dump());
  h.add(src.command.size());
  for (const std::string& arg : src.command) h.add(arg);
  for (const std::string& out : src.outputs) h.add(out);
  for (const fs::path& in : src.inputs) h.add(in.string()).add_file(in);
  for (const fs::path& f : src.files) h.add(f.string()).add_file(f);
  return h.hex();
}

std::string judge_hash(const Case& c, const std::string& input,
                       const std::vector<std::vector<fs::path>>& goldens) {
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
      .add(t.max_differing_pixels);
  const auto add_gates = [&](const std::vector<metric::Gates>& gates) {
    h.add(gates.size());
    for (const metric::Gates& g : gates) {
      h.add(std::string(g.metric->name)).add(g.allow_nonfinite).add(g.limits.size());
      for (const metric::Limit& l : g.limits) h.add(l.stat).add(l.is_max).add(l.limit);
    }
  };
  add_gates(t.gates);
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
    for (const fs::path& g : goldens[i]) {
      h.add(g.parent_path().filename().string()).add_file(g);
      // The region map beside it decides which pixels each region's gates see.
      const fs::path map = region_map(g, c.images[i]);
      if (!t.regions.empty() && fs::is_regular_file(map)) h.add_file(map);
    }
  }
  return h.hex();
}

}  // namespace aosuite::harness

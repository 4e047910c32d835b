#include "harness/case_hash.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <span>

#include "common/content_hash.hpp"
#include "renderer/params.hpp"
#include "renderer/passes/shader_library.hpp"

namespace aosuite::harness {
namespace {

namespace fs = std::filesystem;

using Hasher = ContentHash;

// The build of the code that renders: a rebuilt renderer invalidates every cached render.
const std::string& build_hash() {
  static const std::string hash = [] {
    Dl_info info{};
    if (!dladdr(reinterpret_cast<const void*>(&build_hash), &info) || !info.dli_fname)
      return std::string("unknown");
    return Hasher().add_file(info.dli_fname).hex();
  }();
  return hash;
}

}  // namespace

std::string input_hash(const Case& c, const std::string& gl_description) {
  Hasher h;
  h.add(build_hash()).add(gl_description);
  for (std::string_view name : renderer::shader_names())
    h.add(name).add(renderer::shader_text(name));
  for (const renderer::Mesh& m : c.scene->meshes) {
    h.add(std::span(m.positions))
        .add(std::span(m.normals))
        .add(std::span(m.triangles))
        .add(m.colour)
        .add(m.ground);
  }
  for (const renderer::View& v : c.scene->views) {
    h.add(v.name).add(v.eye).add(v.target).add(v.up).add(v.fovy_degrees).add(v.near);
  }
  h.add(c.view).add(c.technique).add(c.width).add(c.height);
  // Every parameter, whether this technique reads it or not: a stale render is never reused.
  for (const renderer::ParamSpec& spec : renderer::param_specs())
    h.add(spec.key).add(renderer::param_text(spec, c.params));
  return h.hex();
}

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
      .add(t.max_channel_delta);
  const auto add_gates = [&](const std::vector<metric::Gates>& gates) {
    h.add(gates.size());
    for (const metric::Gates& g : gates) {
      h.add(std::string(g.metric->name)).add(g.allow_nonfinite).add(g.limits.size());
      for (const metric::Limit& l : g.limits) h.add(l.stat).add(l.is_max).add(l.limit);
    }
  };
  add_gates(t.gates);
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

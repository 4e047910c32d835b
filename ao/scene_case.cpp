#include "ao/scene_case.hpp"

#include <dlfcn.h>
#include <fmt/format.h>

#include <span>

#include "common/content_hash.hpp"
#include "renderer/passes/shader_library.hpp"

namespace aosuite::ao {
namespace {

namespace rd = aosuite::renderer;
using harness::Case;

// The build of the code that renders: a rebuilt renderer invalidates every cached render.
const std::string& build_hash() {
  static const std::string hash = [] {
    Dl_info info{};
    if (!dladdr(reinterpret_cast<const void*>(&build_hash), &info) || !info.dli_fname)
      return std::string("unknown");
    return ContentHash().add_file(info.dli_fname).hex();
  }();
  return hash;
}

// A parameter's value with its type: a number, a name, a list of numbers.
// Floats go through their shortest text, so 0.012f is 0.012 in JSON, not 0.012000000104...
nlohmann::json typed(const rd::ParamValue& v) {
  const auto number = [](float f) { return std::stod(fmt::format("{}", f)); };
  if (const float* f = std::get_if<float>(&v)) return number(*f);
  if (const auto* list = std::get_if<std::vector<float>>(&v)) {
    nlohmann::json out = nlohmann::json::array();
    for (const float f : *list) out.push_back(number(f));
    return out;
  }
  return std::visit([](const auto& x) { return nlohmann::json(x); }, v);
}

}  // namespace

std::string render_ext(std::string_view image) { return image == "ao_float" ? ".exr" : ".png"; }

std::string SceneCase::input_hash(const Case& c, const std::string& environment) const {
  ContentHash h;
  h.add(build_hash()).add(environment);
  h.add(rd::shaders_hash());
  for (const rd::Mesh& m : scene->meshes) {
    h.add(std::span(m.positions))
        .add(std::span(m.normals))
        .add(std::span(m.triangles))
        .add(m.colour)
        .add(m.ground);
  }
  for (const rd::View& v : scene->views) {
    h.add(v.name).add(v.eye).add(v.target).add(v.up).add(v.fovy_degrees).add(v.near);
  }
  h.add(view).add(technique).add(c.width).add(c.height);
  // Every parameter, whether this technique reads it or not: a stale render is never reused.
  for (const rd::ParamSpec& spec : rd::param_specs())
    h.add(spec.key).add(rd::param_text(spec, params));
  return h.hex();
}

std::vector<std::string> SceneCase::kept_images(const Case& c) const {
  std::vector<std::string> out{"no_ao", "with_ao", "ao_only"};
  if (std::ranges::count(c.images, "ao_float")) out.push_back("ao_float");
  if (c.tolerance.foreground_only) out.push_back("foreground");
  return out;
}

void SceneCase::describe(const Case&, harness::CaseResult& r) const {
  r.labels = {{"scene", scene->name},
              {"view", view},
              {"technique", std::string(rd::technique_name(technique))}};
  for (const rd::ParamSpec& spec : rd::param_specs()) {
    if (rd::applies(spec, technique))
      r.params[std::string(spec.key)] = typed(rd::param_value(spec, params));
  }
}

}  // namespace aosuite::ao

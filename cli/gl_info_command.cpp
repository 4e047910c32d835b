// `aosuite gl-info`: every OpenGL backend and device this machine can open, what each gives
// (vendor, renderer, version, whether it meets the 4.5 core requirement), and which one the
// GL commands would render with under the current --gl / AOSUITE_GL settings, and in which
// pipeline (fragment or compute) when a command names none.
#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "renderer/gl/gl_context.hpp"
#include "renderer/renderer.hpp"

namespace aosuite::cli {
namespace {

namespace rd = aosuite::renderer;

int run_gl_info(bool json) {
  const std::vector<rd::GlProbe> probes = rd::probe_gl_backends();
  std::string selected, error;
  rd::Pipeline pipeline = rd::Pipeline::kFragment;
  try {
    const rd::Renderer renderer;  // its default pipeline is the device's
    selected = renderer.gl_source();
    pipeline = renderer.default_pipeline();
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (json) {
    nlohmann::ordered_json j;
    j["backends"] = nlohmann::json::array();
    for (const rd::GlProbe& p : probes) {
      j["backends"].push_back({{"backend", p.backend},
                               {"source", p.source},
                               {"device", p.device},
                               {"hardware", p.hardware},
                               {"vendor", p.vendor},
                               {"renderer", p.renderer},
                               {"version", p.version},
                               {"meets_requirement", p.meets_requirement},
                               {"error", p.error}});
    }
    j["osmesa_built"] = rd::osmesa_built();
    if (error.empty()) {
      j["selected"] = selected;
      j["pipeline"] = rd::pipeline_name(pipeline);
    } else {
      j["error"] = error;
    }
    fmt::print("{}\n", j.dump(2));
  } else {
    for (const rd::GlProbe& p : probes) {
      const std::string status = !p.error.empty()      ? "unusable: " + p.error
                                 : p.meets_requirement ? "ok"
                                                       : "below OpenGL 4.5 core";
      fmt::print("{:<26} {:<8} {}\n", p.source, p.hardware ? "GPU" : "software", status);
      if (p.error.empty()) fmt::print("  {} | {} | {}\n", p.vendor, p.renderer, p.version);
    }
    if (!rd::osmesa_built()) fmt::print("OSMesa                     not built\n");
    if (error.empty()) {
      fmt::print("renders with: {}\n", selected);
      fmt::print("pipeline: {} (the default on this device; --pipeline fragment|compute)\n",
                 rd::pipeline_name(pipeline));
    } else {
      fmt::print(stderr, "aosuite gl-info: {}\n", error);
    }
  }
  return error.empty() ? kExitSame : kExitError;
}

}  // namespace

void add_gl_info_command(CLI::App& app, int& rc) {
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd =
      app.add_subcommand("gl-info", "List the OpenGL backends and devices this machine has");
  cmd->add_flag("--json", *json, "as JSON");
  guarded(cmd, rc, "gl-info", [json] { return run_gl_info(*json); });
}

}  // namespace aosuite::cli

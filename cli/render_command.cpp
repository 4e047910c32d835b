// `aosuite render`: one scene view through one technique; writes the no-AO, with-AO and
// AO-only PNGs, the AO term as float EXR, and a JSON of parameters and per-pass times.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "ao/statistics.hpp"
#include "cli/commands.hpp"
#include "cli/gl_command_util.hpp"
#include "compare/opencv.hpp"
#include "renderer/renderer.hpp"
#include "renderer/scene/scene.hpp"
#include "renderer/scene/scene_file.hpp"

namespace aosuite::cli {
namespace {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;

struct RenderArgs {
  ao::CaseOptions c;
  std::string out = "reports/render", outputs = "all";
  int runs = 1;
};

int run_render(const RenderArgs& a) {
  rd::Scene scene = rd::load_scene(a.c.scene);
  const rd::View& view = rd::find_view(scene, a.c.view);
  rd::RenderSettings s = ao::case_settings(a.c);
  s.outputs = rd::parse_outputs(a.outputs);

  rd::Renderer renderer;
  // A warm-up frame compiles llvmpipe's shader variants; then the median of the timed runs.
  rd::Images img = renderer.render(scene, view, s);
  std::map<std::string, std::vector<double>> gpu;
  std::vector<double> frame;
  for (int r = 0; r < a.runs; ++r) {
    img = renderer.render(scene, view, s);
    for (const rd::PassTime& t : img.times) gpu[t.pass].push_back(t.gpu_ms);
    frame.push_back(img.frame_ms);
  }
  fs::create_directories(a.out);
  const std::string stem = fmt::format("{}_{}_{}", scene.name, view.name, a.c.technique);
  const fs::path dir(a.out);
  if (!img.no_ao.empty()) write_png_rgba8(dir / (stem + "_no_ao.png"), img.no_ao);
  if (!img.with_ao.empty()) write_png_rgba8(dir / (stem + "_with_ao.png"), img.with_ao);
  if (!img.ao_only.empty()) write_png_rgba8(dir / (stem + "_ao_only.png"), img.ao_only);
  if (!img.ao.empty()) write_exr(dir / (stem + "_ao.exr"), img.ao);

  nlohmann::ordered_json j;
  j["scene"] = scene.name, j["view"] = view.name, j["technique"] = a.c.technique;
  j["width"] = s.width, j["height"] = s.height;
  j["params"] = ao::params_json(s.technique, s.params);
  j["gl"] = renderer.gl_description();
  j["gl_device"] = renderer.gl_source();
  j["pipeline"] = rd::pipeline_name(img.pipeline);
  j["gbuffer"] = rd::gbuffer_name(s.gbuffer);
  j["runs"] = a.runs;
  // Each pass's GPU time (GL_TIME_ELAPSED), and the frame's wall time from the first pass's
  // submission to the last one's end (read-back excluded).
  for (const auto& [pass, times] : gpu) j["median_ms"][pass] = ao::median(times);
  j["median_ms"]["frame_wall"] = ao::median(frame);
  const std::string text = j.dump(2) + "\n";
  write_text(dir / (stem + ".json"), text);
  fmt::print("{}: {}\n", (dir / stem).string(), j["median_ms"].dump());
  if (img.geometry_pixels == 0) {
    fmt::print(stderr,
               "aosuite render: warning: view '{}' of {} draws no geometry (everything clipped "
               "or background; near plane {:g}): the images show only the background\n",
               view.name, scene.name, view.near);
  }
  return kExitSame;
}

void print_views(const std::vector<rd::View>& views) {
  for (const rd::View& v : views) {
    fmt::print("  {:<12} eye ({:g}, {:g}, {:g}) -> ({:g}, {:g}, {:g}), fovy {:g}\n", v.name,
               v.eye.x, v.eye.y, v.eye.z, v.target.x, v.target.y, v.target.z, v.fovy_degrees);
  }
}

nlohmann::json views_json(const std::vector<rd::View>& views) {
  nlohmann::json out = nlohmann::json::array();
  for (const rd::View& v : views) {
    out.push_back({{"name", v.name},
                   {"eye", {v.eye.x, v.eye.y, v.eye.z}},
                   {"target", {v.target.x, v.target.y, v.target.z}},
                   {"up", {v.up.x, v.up.y, v.up.z}},
                   {"fovy_degrees", v.fovy_degrees},
                   {"near", v.near}});
  }
  return out;
}

// `--json`: one object, {"scenes": [{name, kind, file?, meshes?, triangles?, views: [...]}]}.
int run_scenes(const std::vector<std::string>& files, bool json) {
  nlohmann::json scenes = nlohmann::json::array();
  if (!files.empty()) {
    for (const std::string& f : files) {
      const rd::Scene scene = rd::load_scene(f);
      std::size_t triangles = 0;
      for (const rd::Mesh& m : scene.meshes) triangles += m.triangles.size();
      if (json) {
        scenes.push_back({{"name", scene.name},
                          {"kind", "file"},
                          {"file", f},
                          {"meshes", scene.meshes.size()},
                          {"triangles", triangles},
                          {"views", views_json(scene.views)}});
        continue;
      }
      fmt::print("{}: {} meshes, {} triangles\n", f, scene.meshes.size(), triangles);
      print_views(scene.views);
    }
    if (json) fmt::print("{}\n", nlohmann::json{{"scenes", scenes}}.dump());
    return kExitSame;
  }
  for (const std::string& name : rd::builtin_scene_names()) {
    if (json) {
      scenes.push_back({{"name", name},
                        {"kind", "built-in"},
                        {"views", views_json(rd::builtin_scene_views(name))}});
      continue;
    }
    fmt::print("{}\n", name);
    print_views(rd::builtin_scene_views(name));
  }
  for (const std::string& name : rd::downloadable_scene_names()) {
    const fs::path file = rd::downloadable_scene_file(name);
    if (json) {
      scenes.push_back({{"name", name},
                        {"kind", "downloadable"},
                        {"file", file.string()},
                        {"fetched", fs::exists(file)},
                        {"views", views_json(rd::builtin_scene_views(name))}});
      continue;
    }
    fmt::print("{} ({})\n", name,
               fs::exists(file) ? file.string() : "not fetched: run scripts/fetch_assets.sh");
    print_views(rd::builtin_scene_views(name));
  }
  if (json) fmt::print("{}\n", nlohmann::json{{"scenes", scenes}}.dump());
  return kExitSame;
}

}  // namespace

void add_scenes_command(CLI::App& app, int& rc) {
  auto files = std::make_shared<std::vector<std::string>>();
  CLI::App* cmd = app.add_subcommand("scenes", "List built-in scenes and their views");
  auto json = std::make_shared<bool>(false);
  cmd->add_option("files", *files, "scene files (.toml) to check and list instead");
  cmd->add_flag("--json", *json, "print the scenes and their views as one JSON object");
  guarded(cmd, rc, "scenes", [files, json] { return run_scenes(*files, *json); });
}

void add_render_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene view with one AO technique");
  add_case_options(cmd, a->c);
  cmd->add_option("--outputs", a->outputs, "all, or a list of no_ao,with_ao,ao_only,ao_float")
      ->capture_default_str();
  cmd->add_option("--runs", a->runs, "timed runs after one warm-up (median reported)")
      ->capture_default_str();
  cmd->add_option("--out", a->out, "output directory")->capture_default_str();
  guarded(cmd, rc, "render", [a] { return run_render(*a); });
}

}  // namespace aosuite::cli

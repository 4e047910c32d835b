#include "cli/gl_command_util.hpp"

#include <fmt/format.h>

#include <string>

#include "image/exr_file.hpp"
#include "renderer/params.hpp"

namespace aosuite::cli {

namespace rd = aosuite::renderer;
namespace fs = std::filesystem;

void add_case_options(CLI::App* cmd, ao::CaseOptions& o) {
  cmd->add_option("--scene", o.scene,
                  "built-in scene name or scene file (.toml); `aosuite scenes` lists them")
      ->capture_default_str();
  cmd->add_option("--view", o.view, "view name or index (default: the first)");
  cmd->add_option("--technique", o.technique, rd::technique_names("|"))->capture_default_str();
  cmd->add_option("--width", o.width)->capture_default_str();
  cmd->add_option("--height", o.height)->capture_default_str();
  cmd->add_option("--samples", o.samples, "samples per pixel (default: the technique's)");
  cmd->add_option("--radius", o.radius, "radius in scene units");
  std::string keys;
  for (const rd::ParamSpec& p : rd::param_specs()) keys += fmt::format("\n  {}: {}", p.key, p.doc);
  cmd->add_option("--preset", o.preset,
                  "the technique's parameters from a preset file (technique = \"...\", [params]) "
                  "or a built-in preset (tuned), applied before --samples, --radius and --param");
  cmd->add_option("--param", o.params, "KEY=VALUE, repeatable; keys:" + keys);
  add_pipeline_option(cmd, o.pipeline);
  cmd->add_option("--gbuffer", o.gbuffer,
                  "full|depth: the G-buffer rasterised whole, or depth alone with normals "
                  "reconstructed from it (XeGTAO's; untextured images)")
      ->capture_default_str();
}

void add_pipeline_option(CLI::App* cmd, std::string& pipeline) {
  cmd->add_option("--pipeline", pipeline,
                  "fragment|compute: the screen-space passes drawn or dispatched (the same "
                  "images); default: the device's (`aosuite gl-info`)");
}

void write_exr(const fs::path& path, const cv::Mat& image) {
  CV_Assert(image.type() == CV_32FC1 && image.isContinuous());
  aosuite::write_exr(path, image.cols, image.rows, image.ptr<float>());
}

}  // namespace aosuite::cli

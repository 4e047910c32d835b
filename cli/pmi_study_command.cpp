// `aosuite pmi-study`: the PMI paper's Table 1 study and its smoothness claim on one scene's
// object (ao/pmi_study.hpp); prints its progress and its tables.
#include <fmt/format.h>

#include "ao/pmi_study.hpp"
#include "cli/commands.hpp"

namespace aosuite::cli {
namespace {

int run_study(const ao::PmiStudySettings& a) {
  const ao::PmiStudyProgress progress{
      [&a](const std::string& scene, std::size_t polygons, std::size_t vertices, double seconds) {
        fmt::print("{}: {} polygons, {} vertices; ray-traced AO ({} rays per vertex) in {:.1f} s\n",
                   scene, polygons, vertices, a.rays, seconds);
      },
      [](int width, int height, int viewpoints, double seconds) {
        fmt::print(stderr, "{}x{} {} viewpoints: {:.1f} s\n", width, height, viewpoints, seconds);
      }};
  fmt::print("{}", ao::run_pmi_study(a, progress));
  return kExitSame;
}

}  // namespace

void add_pmi_study_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<ao::PmiStudySettings>();
  CLI::App* cmd = app.add_subcommand(
      "pmi-study", "PMI's resolution x viewpoints study: time, agreement with ray-traced AO");
  cmd->add_option("--scene", a->scene, "built-in scene or scene file")->capture_default_str();
  cmd->add_option("--view", a->view, "view for the rendered comparison (default: the first)");
  cmd->add_option("--resolutions", a->resolutions, "item-buffer widths")->delimiter(',');
  cmd->add_option("--viewpoints", a->viewpoints, "viewpoint counts")->delimiter(',');
  cmd->add_option("--rays", a->rays, "rays per vertex of the ray-traced AO")->capture_default_str();
  cmd->add_option("--width", a->width, "rendered comparison width")->capture_default_str();
  cmd->add_option("--height", a->height, "rendered comparison height")->capture_default_str();
  cmd->add_option("--out", a->out)->capture_default_str();
  guarded(cmd, rc, "pmi-study", [a] { return run_study(*a); });
}

}  // namespace aosuite::cli

// `aosuite viewpoints`: viewpoint selection with PMI's channel (ao/viewpoint_study.hpp);
// prints the summary it writes.
#include <fmt/format.h>

#include "ao/viewpoint_study.hpp"
#include "cli/commands.hpp"

namespace aosuite::cli {

void add_viewpoints_command(CLI::App& app, int& rc) {
  auto a = std::make_shared<ao::ViewpointStudySettings>();
  CLI::App* cmd = app.add_subcommand(
      "viewpoints", "PMI viewpoint selection: VMI and PMI(v) per viewpoint, best/worst views");
  cmd->add_option("--scene", a->scene, "built-in scene or scene file")->capture_default_str();
  cmd->add_option("--viewpoints", a->viewpoints, "12, 42, 162, 642 or 2562")->capture_default_str();
  cmd->add_option("--resolution", a->resolution, "item-buffer width (height 3/4 of it)")
      ->capture_default_str();
  cmd->add_option("--importance-best", a->importance_best,
                  "0: p(v) by projected area; k: the k best views share 99 %")
      ->capture_default_str();
  cmd->add_flag("--colour-ao", a->colour_ao,
                "also write colour AO (eq. 12; viewpoint colours (1 + direction) / 2) as a PLY");
  cmd->add_option("--width", a->width, "view image width")->capture_default_str();
  cmd->add_option("--height", a->height, "view image height")->capture_default_str();
  cmd->add_option("--out", a->out)->capture_default_str();
  guarded(cmd, rc, "viewpoints", [a] {
    fmt::print("{}\n", ao::run_viewpoint_study(*a).dump());
    return kExitSame;
  });
}

}  // namespace aosuite::cli

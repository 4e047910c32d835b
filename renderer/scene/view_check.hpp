// The one check of a camera view, shared by the renderer (before it draws) and the scene-file
// loader (so `aosuite scenes` refuses exactly the views `aosuite render` would).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "renderer/scene/scene.hpp"

namespace aosuite::renderer {

struct ViewProblem {
  std::string_view field;  // the View member at fault: "near", "fovy_degrees", "eye", ...
  std::string why;         // e.g. "near must be a positive normal float (>= 1.2e-38)"
};

// What makes `view` unrenderable, or nothing: a near plane that is not a positive normal float
// (0, denormals and NaN make every depth 0), a field of view outside [0.1, 180) degrees, eye and
// target not finite or equal, an up that is not finite. An up parallel to the view direction is
// renderable (make_camera picks another); scene files refuse it on their own.
std::optional<ViewProblem> view_problem(const View& view);

}  // namespace aosuite::renderer

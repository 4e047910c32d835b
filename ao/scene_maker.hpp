// Renders scene cases (ao/scene_cases.hpp) on one thread, in its own GL context.
#pragma once

#include <memory>

#include "harness/case_kind.hpp"

namespace aosuite::ao {

// Makes the GL context now; `env` (when given) gets the GL implementation and its platform key.
std::unique_ptr<harness::Maker> make_scene_maker(harness::Environment* env);

}  // namespace aosuite::ao

// The AO bench's suite cases: a [[case]] with `scene` renders it (each view x each technique)
// with the renderer and gates its images. Registered with the harness as the kind "render"
// (harness/case_kind.hpp); the harness itself never sees a scene.
#pragma once

#include "ao/scene_case.hpp"

namespace aosuite::ao {

// Registers the kind with the harness: suites may then hold scene cases.
void register_scene_cases();

}  // namespace aosuite::ao

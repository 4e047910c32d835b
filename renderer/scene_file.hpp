// Scenes from TOML files (format in README.md, "Scene files"), and the one entry point that
// takes either a built-in scene's name or a scene file's path.
#pragma once

#include <filesystem>
#include <string_view>

#include "renderer/scene.hpp"

namespace aosuite::renderer {

// Reads a scene file; mesh files are found relative to its folder. Throws aosuite::FileError
// "<file>:<line>:<column>: <reason>" for malformed TOML, unknown keys, wrong types, missing or
// out-of-range values, duplicate view names, no views, and meshes that cannot be loaded.
Scene load_scene_file(const std::filesystem::path& path);

// A path ending in .toml is a scene file; anything else names a built-in scene.
Scene load_scene(std::string_view name_or_path);

}  // namespace aosuite::renderer

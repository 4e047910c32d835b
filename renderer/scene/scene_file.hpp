// Scenes from TOML files (format in docs/rendering.md, "Scene files"), and the one entry point that
// takes either a built-in scene's name or a scene file's path.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string_view>

#include "renderer/scene/scene.hpp"

namespace aosuite::renderer {

// Scene files may make at most this many triangles in all (docs/rendering.md, "Scene files"); the
// environment variable AOSUITE_MAX_TRIANGLES replaces it.
inline constexpr std::uint64_t kDefaultMaxSceneTriangles = 50'000'000;
// AOSUITE_MAX_TRIANGLES when set (a positive integer, else std::invalid_argument), else the
// default.
std::uint64_t max_scene_triangles();

// Reads a scene file; mesh files are found relative to its folder. Throws aosuite::FileError
// "<file>:<line>:<column>: <reason>" for malformed TOML, unknown keys, wrong types, missing or
// out-of-range values, views the renderer would refuse (view_check.hpp), duplicate view names,
// no views, meshes that cannot be loaded, a mesh file whose SHA-256 is not its `sha256` pin
// (checked before the mesh is parsed), and more triangles than max_scene_triangles() (counted for
// primitives before any geometry is made).
Scene load_scene_file(const std::filesystem::path& path);

// A path ending in .toml is a scene file; anything else names a built-in scene.
Scene load_scene(std::string_view name_or_path);

}  // namespace aosuite::renderer

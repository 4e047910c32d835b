// Triangle meshes from files: PLY (ASCII and binary), OBJ and OFF, read through assimp, and
// STL (ASCII and binary), read by stl_mesh.hpp.
#pragma once

#include <filesystem>
#include <vector>

#include "renderer/scene/mesh.hpp"

namespace aosuite::renderer {

// Every mesh of the file merged into one, triangulated (points and lines dropped), with the
// file's normals when it has usable ones and computed normals otherwise (an STL's: per facet).
// Degenerate and zero-area triangles are kept (compute_normals ignores them), but for an STL's
// slivers. Throws aosuite::FileError "<file>: <reason>" for an unreadable, truncated or
// malformed file, a non-finite position, an index out of range or a file without triangles.
Mesh load_mesh(const std::filesystem::path& path);
// The same from the file's bytes, read by the caller: a scene file that pins the mesh's SHA-256
// parses the very bytes it hashed. `path` names the file in errors and gives its format.
Mesh load_mesh(const std::filesystem::path& path, std::vector<unsigned char> bytes);

}  // namespace aosuite::renderer

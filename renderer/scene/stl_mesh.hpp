// STL, ASCII or binary, read here rather than through assimp: the format is small, and a CAD
// part's facets need flat normals, which assimp's smoothing would not keep.
#pragma once

#include <span>
#include <string_view>

#include "renderer/scene/mesh.hpp"

namespace aosuite::renderer {

// The file's triangles, each with its own normal from its corners (an STL's stored normal may
// be anything, often zero), so a modelled part keeps its creases; corners equal in position
// and normal are welded. A sliver, whose smallest angle's sine is under 1e-4, has no normal to
// speak of and is left out: it covers no pixel and hardly a ray. Binary when the size is 84 +
// 50 bytes a triangle by the count at byte 80 (even if the header begins with "solid", as some
// exporters write it), else ASCII. Throws aosuite::FileError "<name>: <reason>" (with the line
// for ASCII) for a file that is neither, is truncated, holds a non-finite coordinate or has no
// triangle left.
Mesh read_stl(std::string_view name, std::span<const unsigned char> bytes);

}  // namespace aosuite::renderer

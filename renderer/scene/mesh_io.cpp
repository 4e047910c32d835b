#include "renderer/scene/mesh_io.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cmath>

#include "common/file_io.hpp"
#include "common/printable.hpp"
#include "renderer/scene/mesh_check.hpp"
#include "renderer/scene/stl_mesh.hpp"

namespace aosuite::renderer {
namespace {

// `why` may quote the file (assimp's messages do): escaped, as the path is.
[[noreturn]] void fail(const std::filesystem::path& path, std::string_view why) {
  throw FileError(printable(fmt::format("{}: {}", path.string(), why)));
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool finite(const aiVector3D& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The file's normals when every one is finite and non-zero, unit length; else none.
std::vector<glm::vec3> usable_normals(const aiMesh& m) {
  if (!m.HasNormals()) return {};
  std::vector<glm::vec3> normals(m.mNumVertices);
  for (unsigned i = 0; i < m.mNumVertices; ++i) {
    const aiVector3D& n = m.mNormals[i];
    const float len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (!(len > 0 && std::isfinite(len))) return {};
    normals[i] = glm::vec3(n.x, n.y, n.z) / len;
  }
  return normals;
}

// One assimp mesh's triangles (its points and lines dropped) as a Mesh with normals, its
// positions multiplied by `unscale` (a power of two: exact).
Mesh triangles_of(const aiMesh& m, float unscale) {
  Mesh out;
  out.positions.reserve(m.mNumVertices);
  for (unsigned i = 0; i < m.mNumVertices; ++i) {
    out.positions.emplace_back(m.mVertices[i].x, m.mVertices[i].y, m.mVertices[i].z);
    out.positions.back() *= unscale;
  }
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    if (face.mNumIndices == 3) {
      out.triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
    }
  }
  out.normals = usable_normals(m);
  if (out.normals.empty()) compute_normals(out);
  return out;
}

// Turns every material statement of an OBJ (mtllib, usemtl, wherever assimp's lenient parser
// would find one) into a comment: AO needs no material, and assimp 5.2 crashes opening a
// material library whose name holds odd bytes from memory (fuzz/corpus/mesh/crash-assimp-*,
// found by the fuzz smoke).
void drop_materials(std::vector<unsigned char>& obj) {
  for (const std::string_view word : {"mtllib", "usemtl"}) {
    const auto* w = reinterpret_cast<const unsigned char*>(word.data());
    for (auto at = obj.begin(); (at = std::search(at, obj.end(), w, w + word.size())) != obj.end();
         ++at)
      *at = '#';
  }
}

// assimp 5.2's weld (aiProcess_JoinIdenticalVertices) joins distinct corners of a small mesh,
// by a tolerance that is not relative to its size: a cube 1e-6 or 1e-8 units wide lost two of
// its eight corners, one 1e-5 or 1e-4 wide kept them. A mesh smaller than an eighth of a unit
// (the dragon, 0.2, is the smallest measured here) is welded scaled by the power of two that
// brings its largest coordinate to [1, 2), so it is welded as it would be at that size; the
// scale is undone after, exactly. Larger meshes are welded as they come, as they always were.
float weld_scale(const aiScene& scene) {
  float largest = 0;
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    const aiMesh& m = *scene.mMeshes[i];
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      largest = std::max({largest, std::abs(m.mVertices[v].x), std::abs(m.mVertices[v].y),
                          std::abs(m.mVertices[v].z)});
    }
  }
  return largest > 0 && largest < 0.125f ? std::ldexp(1.0f, -std::ilogb(largest)) : 1.0f;
}

void scale_positions(const aiScene& scene, float scale) {
  if (scale == 1) return;
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    aiMesh& m = *scene.mMeshes[i];  // the importer's own scene, still to be post-processed
    for (unsigned v = 0; v < m.mNumVertices; ++v) m.mVertices[v] *= scale;
  }
}

// The file's format from its extension, refused before any byte is read if it is none of four.
std::string mesh_format(const std::filesystem::path& path) {
  std::string ext = lower_extension(path);
  if (ext != ".ply" && ext != ".obj" && ext != ".off" && ext != ".stl") {
    fail(path, "unsupported mesh format (expected .ply, .obj, .off or .stl)");
  }
  return ext;
}

Mesh parse_mesh(const std::filesystem::path& path, const std::string& ext,
                std::vector<unsigned char> bytes) {
  if (ext == ".stl") return read_stl(path.string(), bytes);
  if (ext == ".ply") {
    check_ply(path.string(), bytes);
    mend_ply_header_end(path.string(), bytes);
  }
  if (ext == ".off") check_off(path.string(), bytes);
  if (ext == ".obj") {
    // OBJ is text: a NUL byte means it is not one.
    if (const auto nul = std::find(bytes.begin(), bytes.end(), 0); nul != bytes.end())
      fail(path, fmt::format("a NUL byte at offset {}: not an OBJ text file", nul - bytes.begin()));
    // A UTF-8 byte-order mark (Windows editors write one) is no part of the first line.
    if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF)
      bytes.erase(bytes.begin(), bytes.begin() + 3);
    check_obj(path.string(), bytes);
    drop_materials(bytes);
  }

  // Assimp logs only through a DefaultLogger, which is never created here, so it stays quiet.
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(
      bytes.data(), bytes.size(), aiProcess_ValidateDataStructure, ext.c_str() + 1);
  if (!scene) fail(path, importer.GetErrorString());
  // Before vertices are welded, so a NaN cannot hide in a merged vertex; and before
  // triangulation, whose assertion (assimp 5.2) aborts the process on a face of no vertices
  // (a PLY face list of length 0).
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
    const aiMesh& m = *scene->mMeshes[i];
    if (!std::all_of(m.mVertices, m.mVertices + m.mNumVertices, finite)) {
      fail(path, "a vertex position is NaN or infinite");
    }
    if (std::any_of(m.mFaces, m.mFaces + m.mNumFaces,
                    [](const aiFace& f) { return f.mNumIndices == 0; })) {
      fail(path, "a face with no vertices");
    }
  }
  // OBJ and OFF readers give every face its own vertices; welding restores shared ones so
  // computed normals are smooth. Node transforms (OBJ groups) are baked in.
  const float scale = weld_scale(*scene);
  scale_positions(*scene, scale);
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                       aiProcess_PreTransformVertices);
  if (!scene) fail(path, importer.GetErrorString());
  Mesh merged;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i)
    append_mesh(merged, triangles_of(*scene->mMeshes[i], 1 / scale));
  if (merged.triangles.empty()) fail(path, "no triangles");
  // Degenerate triangles beside real ones draw nothing and are kept; a mesh of nothing else
  // would draw nothing at all, so it is refused, as an STL file of them is (stl_mesh.cpp).
  const auto has_area = [&](const glm::uvec3& t) {
    const glm::dvec3 a(merged.positions[t.x]), b(merged.positions[t.y]), c(merged.positions[t.z]);
    return glm::dot(glm::cross(b - a, c - a), glm::cross(b - a, c - a)) > 0;
  };
  if (std::none_of(merged.triangles.begin(), merged.triangles.end(), has_area))
    fail(path, "no triangle has an area: every one has its corners on a line or at one point");
  return merged;
}

}  // namespace

Mesh load_mesh(const std::filesystem::path& path) {
  const std::string ext = mesh_format(path);
  std::vector<unsigned char> bytes;
  try {
    bytes = read_file(path);
  } catch (const FileError& e) {
    throw FileError(printable(e.what()));  // names the path
  }
  return parse_mesh(path, ext, std::move(bytes));
}

Mesh load_mesh(const std::filesystem::path& path, std::vector<unsigned char> bytes) {
  const std::string ext = mesh_format(path);
  return parse_mesh(path, ext, std::move(bytes));
}

}  // namespace aosuite::renderer

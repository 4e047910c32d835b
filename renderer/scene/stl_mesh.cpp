#include "renderer/scene/stl_mesh.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_map>
#include <vector>

#include "renderer/scene/text_tokens.hpp"

namespace aosuite::renderer {
namespace {

using Triangle = std::array<glm::vec3, 3>;

[[noreturn]] void fail(std::string_view name, std::string_view why) {
  throw FileError(printable(fmt::format("{}: {}", name, why)));
}

std::uint32_t u32_le(const unsigned char* p) {
  return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 |
         std::uint32_t{p[3]} << 24;
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// 80 bytes of header, the triangle count, then 50 bytes a triangle: its normal, three corners
// (little-endian float32) and two attribute bytes.
std::vector<Triangle> binary_triangles(std::string_view name, std::span<const unsigned char> b) {
  const std::uint32_t count = u32_le(b.data() + 80);
  std::vector<Triangle> out(count);
  for (std::uint32_t t = 0; t < count; ++t) {
    const unsigned char* at = b.data() + 84 + std::size_t{50} * t + 12;
    for (glm::vec3& corner : out[t]) {
      for (int k = 0; k < 3; ++k, at += 4) corner[k] = std::bit_cast<float>(u32_le(at));
      if (!finite(corner)) {
        fail(name, fmt::format("triangle {} of {}: a corner is NaN or infinite", t + 1, count));
      }
    }
  }
  return out;
}

bool keyword(std::string_view token, std::string_view word) {
  return token.size() == word.size() &&
         std::equal(token.begin(), token.end(), word.begin(),
                    [](char a, char b) { return (a | 0x20) == b; });  // exporters differ in case
}

// solid NAME, then per facet: facet normal X Y Z / outer loop / vertex X Y Z (three) / endloop
// / endfacet; endsolid [NAME]. Several solids may follow one another. The stored normal's
// values are not read: they are not used, and some exporters write "nan" there.
std::vector<Triangle> ascii_triangles(std::string_view name, std::string_view text) {
  text::Tokens in(name, text);
  std::vector<Triangle> out;
  const auto expect = [&](std::string_view word) {
    const std::string_view t = in.next();
    if (!keyword(t, word)) {
      in.fail(t.empty() ? fmt::format("truncated: '{}' missing", word)
                        : fmt::format("'{}' where '{}' was expected", t.substr(0, 64), word));
    }
  };
  for (std::string_view t = in.next(); !t.empty(); t = in.next()) {
    if (!keyword(t, "solid"))
      in.fail(fmt::format("'{}' where 'solid' was expected", t.substr(0, 64)));
    in.rest_of_line();  // the solid's name
    for (t = in.next(); keyword(t, "facet"); t = in.next()) {
      expect("normal");
      for (int k = 0; k < 3; ++k) {
        if (in.next().empty()) in.fail("truncated: a facet normal's value missing");
      }
      expect("outer"), expect("loop");
      Triangle& tri = out.emplace_back();
      for (glm::vec3& corner : tri) {
        expect("vertex");
        for (int k = 0; k < 3; ++k) {
          corner[k] = static_cast<float>(in.number<double>(
              [&] { return fmt::format("vertex coordinate of triangle {}", out.size()); }));
        }
        if (!finite(corner)) in.fail("a vertex coordinate is NaN or infinite (as a float)");
      }
      expect("endloop"), expect("endfacet");
    }
    if (!keyword(t, "endsolid")) {
      in.fail(t.empty()
                  ? std::string("truncated: 'endsolid' missing")
                  : fmt::format("'{}' where 'facet' or 'endsolid' was expected", t.substr(0, 64)));
    }
    in.rest_of_line();
  }
  return out;
}

// The triangle's unit normal, or nothing for a sliver: |u × v| = |u||v| sin(angle between
// them), and the smallest angle lies between the two longest edges.
std::optional<glm::vec3> facet_normal(const Triangle& t) {
  const glm::dvec3 a(t[0]), u = glm::dvec3(t[1]) - a, v = glm::dvec3(t[2]) - a,
                            w = glm::dvec3(t[2]) - glm::dvec3(t[1]);
  const glm::dvec3 n = glm::cross(u, v);
  const double len = glm::length(n), lu = glm::length(u), lv = glm::length(v), lw = glm::length(w);
  if (!(len > 1e-4 * std::max({lu * lv, lu * lw, lv * lw}))) return std::nullopt;
  // Made unit in float as well, as mesh_io.cpp makes a file's normals: an STL and the PLY
  // that scripts/stl_to_ply.js writes from it give the same mesh to the bit.
  const glm::vec3 f(n / len);
  return f / std::sqrt(f.x * f.x + f.y * f.y + f.z * f.z);
}

struct CornerHash {
  std::size_t operator()(const std::array<float, 6>& k) const {
    std::size_t h = 0;
    for (float f : k) h = h * 1000003u ^ std::hash<float>()(f);
    return h;
  }
};

Mesh welded(std::string_view name, const std::vector<Triangle>& triangles) {
  Mesh mesh;
  std::unordered_map<std::array<float, 6>, unsigned, CornerHash> index;
  for (const Triangle& t : triangles) {
    const std::optional<glm::vec3> n = facet_normal(t);
    if (!n) continue;
    glm::uvec3 face;
    for (int k = 0; k < 3; ++k) {
      const std::array<float, 6> key{t[k].x, t[k].y, t[k].z, n->x, n->y, n->z};
      const auto [at, added] = index.try_emplace(key, static_cast<unsigned>(mesh.positions.size()));
      if (added) {
        if (mesh.positions.size() == std::numeric_limits<unsigned>::max()) {
          fail(name, "more vertices than 32-bit indices address");
        }
        mesh.positions.push_back(t[k]), mesh.normals.push_back(*n);
      }
      face[k] = at->second;
    }
    mesh.triangles.push_back(face);
  }
  if (mesh.triangles.empty()) {
    fail(name, triangles.empty() ? "no triangles"
                                 : "no triangles left: every one is a sliver or of no area");
  }
  return mesh;
}

}  // namespace

Mesh read_stl(std::string_view name, std::span<const unsigned char> bytes) {
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (bytes.size() >= 84 && bytes.size() == 84 + std::uint64_t{50} * u32_le(bytes.data() + 80)) {
    return welded(name, binary_triangles(name, bytes));
  }
  // Some exporters indent the whole file, "solid" too, or write it in capitals.
  const std::string_view start =
      text.substr(std::min(text.find_first_not_of(" \t\r\n"), text.size()));
  if (keyword(start.substr(0, 5), "solid")) {
    if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
      fail(name, fmt::format("a NUL byte at offset {} in an ASCII STL (or a binary one whose "
                             "size does not match its triangle count)",
                             nul));
    }
    return welded(name, ascii_triangles(name, text));
  }
  if (bytes.size() < 84)
    fail(name, "not an STL file: no 'solid' and shorter than a binary STL's 84-byte header");
  const std::uint64_t count = u32_le(bytes.data() + 80);
  fail(name, fmt::format("not an STL file: no 'solid', and {} bytes where a binary STL of {} "
                         "triangles has 84 + 50 x {} = {}",
                         bytes.size(), count, count, 84 + 50 * count));
}

}  // namespace aosuite::renderer

// STL meshes (renderer/scene/stl_mesh.hpp) through load_mesh: ASCII and binary agree, facets
// keep their own normals, slivers are dropped, and every bad file is one line naming it.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "common/file_io.hpp"
#include "png_fixture.hpp"
#include "renderer/scene/mesh_io.hpp"

namespace aosuite::renderer {
namespace {

using Corners = std::array<glm::vec3, 3>;

// A unit tetrahedron, outward winding, and a sliver (collinear corners) after it.
const std::vector<Corners> kTetra = {
    {glm::vec3(0, 0, 0), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0)},  // -z
    {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1)},  // -y
    {glm::vec3(0, 0, 0), glm::vec3(0, 0, 1), glm::vec3(0, 1, 0)},  // -x
    {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)},  // the slanted face
};
const Corners kSliver = {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(2, 0, 0)};

std::string ascii_stl(const std::vector<Corners>& triangles, std::string_view normal = "0 0 0") {
  std::string s = "solid part\n";
  for (const Corners& t : triangles) {
    s += fmt::format("  facet normal {}\n    outer loop\n", normal);
    for (const glm::vec3& c : t) s += fmt::format("      vertex {} {} {}\n", c.x, c.y, c.z);
    s += "    endloop\n  endfacet\n";
  }
  return s + "endsolid part\n";
}

// `header` fills the first bytes of the 80-byte header (some exporters begin it with "solid").
std::string binary_stl(const std::vector<Corners>& triangles, std::string_view header = "") {
  std::string s(80, '\0');
  s.replace(0, header.size(), header);
  const auto put = [&](auto v) {
    char b[4];
    std::memcpy(b, &v, 4);  // little-endian hosts only, as the format
    s.append(b, 4);
  };
  put(static_cast<std::uint32_t>(triangles.size()));
  for (const Corners& t : triangles) {
    for (int k = 0; k < 3; ++k) put(0.0f);  // the stored normal: unused
    for (const glm::vec3& c : t) put(c.x), put(c.y), put(c.z);
    s.append(2, '\0');
  }
  return s;
}

class StlFiles : public ::testing::Test {
 protected:
  std::filesystem::path file(const std::string& name, std::string_view bytes) {
    const std::filesystem::path p = dir_.path() / name;
    write_text(p, bytes);
    return p;
  }
  std::string error_of(const std::string& name, std::string_view bytes) {
    const std::filesystem::path p = file(name, bytes);
    try {
      load_mesh(p);
    } catch (const FileError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(p.string() + ":", 0), 0u) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      return what;
    }
    ADD_FAILURE() << name << " was read";
    return {};
  }
  test::TempDir dir_;
};

TEST_F(StlFiles, AsciiAndBinaryGiveTheSameFacetedMesh) {
  const Mesh ascii = load_mesh(file("t.stl", ascii_stl(kTetra)));
  ASSERT_EQ(ascii.triangles.size(), 4u);
  // Each face has its own corners (12), so the tetrahedron keeps its creases: no two faces
  // share a normal.
  ASSERT_EQ(ascii.positions.size(), 12u);
  const glm::vec3 expected[] = {{0, 0, -1}, {0, -1, 0}, {-1, 0, 0}, glm::normalize(glm::vec3(1))};
  for (int f = 0; f < 4; ++f) {
    for (int k = 0; k < 3; ++k) {
      const unsigned v = ascii.triangles[f][k];
      EXPECT_EQ(ascii.positions[v], kTetra[f][k]);
      EXPECT_NEAR(glm::distance(ascii.normals[v], expected[f]), 0.0f, 1e-6f) << f;
    }
  }
  for (const std::string_view header : {"", "solid made by an exporter that says so"}) {
    const Mesh binary = load_mesh(file("b.stl", binary_stl(kTetra, header)));
    EXPECT_EQ(binary.positions, ascii.positions);
    EXPECT_EQ(binary.normals, ascii.normals);
    EXPECT_EQ(binary.triangles, ascii.triangles);
  }
}

TEST_F(StlFiles, CornersOfCoplanarFacetsAreWelded) {
  // A square as two triangles: four corners, not six.
  const std::vector<Corners> square = {
      {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0)},
      {glm::vec3(0, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)}};
  const Mesh m = load_mesh(file("s.stl", binary_stl(square)));
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.positions.size(), 4u);
}

TEST_F(StlFiles, SliversAreDroppedAndStoredNormalsIgnored) {
  std::vector<Corners> with_sliver = kTetra;
  with_sliver.insert(with_sliver.begin() + 1, kSliver);
  // "nan" in the stored normal, as some exporters write it: not read.
  const Mesh m = load_mesh(file("t.stl", ascii_stl(with_sliver, "nan nan nan")));
  EXPECT_EQ(m.triangles.size(), 4u);
  EXPECT_EQ(m.positions, load_mesh(file("u.stl", binary_stl(kTetra))).positions);
  EXPECT_NE(error_of("slivers.stl", binary_stl({kSliver, kSliver})).find("every one is a sliver"),
            std::string::npos);
}

TEST_F(StlFiles, SeveralSolidsUpperCaseKeywordsAndIndentationAreRead) {
  std::string text = ascii_stl({kTetra[0], kTetra[1]}) + ascii_stl({kTetra[2], kTetra[3]});
  for (const char* word : {"solid", "facet", "vertex", "endloop"}) {
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
      for (std::size_t i = 0; i < std::strlen(word); ++i) text[at + i] = char(text[at + i] - 32);
  }
  EXPECT_EQ(load_mesh(file("two.stl", text)).triangles.size(), 4u);
  EXPECT_EQ(text.rfind("SOLID", 0), 0u) << "the first keyword is in capitals too";
  // Indented as a whole, as stl@1.1.1's teapot.stl is.
  EXPECT_EQ(load_mesh(file("indented.stl", "  " + text)).triangles.size(), 4u);
}

TEST_F(StlFiles, EveryCutOfABinaryFileIsRefused) {
  const std::string whole = binary_stl(kTetra);
  for (std::size_t n = 0; n < whole.size(); ++n) error_of("cut.stl", whole.substr(0, n));
}

TEST_F(StlFiles, EveryCutOfAnAsciiFileAtALineIsRefusedWithItsLine) {
  const std::string whole = ascii_stl(kTetra);
  int line = 1;
  for (std::size_t at = whole.find('\n'); at + 1 < whole.size(); at = whole.find('\n', at + 1)) {
    ++line;
    const std::string e = error_of("cut.stl", whole.substr(0, at + 1));
    EXPECT_NE(e.find(fmt::format("cut.stl:{}: truncated", line)), std::string::npos) << e;
  }
}

TEST_F(StlFiles, BadFilesAreOneLineNamingTheProblem) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "no 'solid' and shorter than a binary STL's 84-byte header"},
      {binary_stl({}), "no triangles"},
      {binary_stl(kTetra) + "x", "where a binary STL of 4 triangles has 84 + 50 x 4 = 284"},
      {std::string("solid x\n\0", 9), "a NUL byte at offset 8"},
      {"solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 zero\n", ":4: 'zero' is not a valid"},
      {"solid x\nfacet normal 0 0 0\nouter loop\nvertex 1e39 0 0\n",
       ":4: a vertex coordinate is NaN or infinite"},
      {"solid x\nfacet normal 0 0 0\nouter loop\nvertex nan 0 0\n",
       ":4: a vertex coordinate is NaN"},
      {"solid x\nfacet normal 0 0 0\ninner loop\n", ":3: 'inner' where 'outer' was expected"},
      {"solid x\nendsolid x\nrubbish\n", ":3: 'rubbish' where 'solid' was expected"},
  };
  for (const auto& [bytes, message] : cases) {
    const std::string e = error_of("bad.stl", bytes);
    EXPECT_NE(e.find(message), std::string::npos) << e;
  }
  std::string nan = binary_stl(kTetra);
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan.data() + 84 + 50 * 2 + 12 + 4, &q, 4);
  EXPECT_NE(error_of("nan.stl", nan).find("triangle 3 of 4: a corner is NaN or infinite"),
            std::string::npos);
}

}  // namespace
}  // namespace aosuite::renderer

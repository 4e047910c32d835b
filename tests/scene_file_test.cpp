// Mesh files and scene files as users hand them over: every supported format, broken files
// refused with the file named (and the line for text), placements that do what they say.
// No OpenGL: nothing here renders.
#include "renderer/scene_file.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <glm/gtc/epsilon.hpp>
#include <regex>

#include "compare/image_io.hpp"
#include "png_fixture.hpp"
#include "renderer/mesh_io.hpp"

namespace aosuite::renderer {
namespace {

namespace fs = std::filesystem;

fs::path write(const fs::path& path, std::string_view text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The message of the FileError `f` throws; fails the test if it throws nothing.
template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const FileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no FileError thrown";
  return {};
}

std::pair<glm::vec3, glm::vec3> bounds(const Mesh& m) {
  glm::vec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::vec3& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return {lo, hi};
}

void expect_near(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
  EXPECT_TRUE(glm::all(glm::epsilonEqual(a, b, eps)))
      << a.x << "," << a.y << "," << a.z << " vs " << b.x << "," << b.y << "," << b.z;
}

void expect_unit_normals(const Mesh& m) {
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

// A tetrahedron, as ASCII PLY and as binary PLY of either byte order.
constexpr float kTetra[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
constexpr int kTetraFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
const char* const kPlyHeader =
    "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 4\nproperty list uchar int vertex_indices\nend_header\n";

std::string tetra_ascii_ply() {
  std::string s = std::string("ply\nformat ascii 1.0\n") + kPlyHeader;
  for (const auto& v : kTetra) s += fmt::format("{} {} {}\n", v[0], v[1], v[2]);
  for (const auto& f : kTetraFaces) s += fmt::format("3 {} {} {}\n", f[0], f[1], f[2]);
  return s;
}

template <typename T>
void put(std::string& out, T value, bool big) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big) std::reverse(std::begin(bytes), std::end(bytes));
  out.append(bytes, sizeof(T));
}

std::string tetra_binary_ply(bool big) {
  std::string s = std::string("ply\nformat ") +
                  (big ? "binary_big_endian" : "binary_little_endian") + " 1.0\n" + kPlyHeader;
  for (const auto& v : kTetra) {
    for (float c : v) put(s, c, big);
  }
  for (const auto& f : kTetraFaces) {
    s.push_back(3);
    for (int i : f) put(s, i, big);
  }
  return s;
}

class MeshFiles : public ::testing::Test {
 protected:
  fs::path file(const std::string& name, std::string_view text) { return write(dir_ / name, text); }
  test::TempDir dir_;
};

TEST_F(MeshFiles, PlyAsciiAndBinaryOfBothByteOrdersAgree) {
  const Mesh ascii = load_mesh(file("t.ply", tetra_ascii_ply()));
  ASSERT_EQ(ascii.triangles.size(), 4u);
  ASSERT_EQ(ascii.positions.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    expect_near(ascii.positions[i], {kTetra[i][0], kTetra[i][1], kTetra[i][2]});
    EXPECT_EQ(ascii.triangles[i],
              glm::uvec3(kTetraFaces[i][0], kTetraFaces[i][1], kTetraFaces[i][2]));
  }
  expect_unit_normals(ascii);
  // The corner at the origin is shared by three faces whose normals are -x, -y, -z.
  expect_near(ascii.normals[0], glm::normalize(glm::vec3(-1, -1, -1)));
  for (bool big : {false, true}) {
    const Mesh binary = load_mesh(file(big ? "be.ply" : "le.ply", tetra_binary_ply(big)));
    EXPECT_EQ(binary.positions, ascii.positions);
    EXPECT_EQ(binary.triangles, ascii.triangles);
  }
}

TEST_F(MeshFiles, ObjQuadIsTriangulatedWeldedAndGetsNormals) {
  const Mesh m = load_mesh(file("q.obj",
                                "# a unit square facing +z\nv 0 0 0\nv 1 0 0\nv 1 1 0\n"
                                "v 0 1 0\nf 1 2 3 4\n"));
  EXPECT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.positions.size(), 4u);  // faces share their vertices again
  expect_unit_normals(m);
  for (const glm::vec3& n : m.normals) expect_near(n, {0, 0, 1});
}

TEST_F(MeshFiles, ObjKeepsTheFilesOwnNormals) {
  // The file's normal points away from the geometric one: it must be kept, not recomputed.
  const Mesh m =
      load_mesh(file("n.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -2\nf 1//1 2//1 3//1\n"));
  ASSERT_EQ(m.normals.size(), 3u);
  for (const glm::vec3& n : m.normals) expect_near(n, {0, 0, -1});
}

TEST_F(MeshFiles, ObjGroupsAreMergedAndLinesDropped) {
  const Mesh m = load_mesh(file("g.obj",
                                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ng a\nf 1 2 3\ng b\nf 1 2 4\n"
                                "l 1 4\n"));
  EXPECT_EQ(m.triangles.size(), 2u);
  for (const glm::uvec3& t : m.triangles)
    EXPECT_LT(glm::max(t.x, glm::max(t.y, t.z)), m.positions.size());
}

TEST_F(MeshFiles, OffPolygonsAreTriangulated) {
  // A square pyramid: a quad base and four triangles.
  const Mesh m = load_mesh(file("p.off",
                                "OFF\n# comment\n5 5 0\n0 0 0\n1 0 0\n1 0 1\n0 0 1\n0.5 1 0.5\n"
                                "4 0 1 2 3\n3 0 4 1\n3 1 4 2\n3 2 4 3\n3 3 4 0\n"));
  EXPECT_EQ(m.triangles.size(), 6u);
  expect_unit_normals(m);
}

TEST_F(MeshFiles, DegenerateTrianglesAreKeptHarmless) {
  // A zero-area sliver (collinear points), a triangle repeating a vertex, and a good one.
  const Mesh m =
      load_mesh(file("d.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\nf 1 2 4\n"));
  EXPECT_EQ(m.triangles.size(), 3u);
  expect_unit_normals(m);
  expect_near(m.normals[2], {0, 1, 0});  // used only by the sliver: the documented fallback
  expect_near(m.normals[3], {0, 0, 1});
}

TEST_F(MeshFiles, NonFinitePositionsAreRefused) {
  const fs::path ply = file(
      "nan.ply", std::regex_replace(tetra_ascii_ply(), std::regex("\n1 0 0\n"), "\nnan 0 0\n"));
  EXPECT_NE(error_of([&] { load_mesh(ply); }).find(ply.string() + ": a vertex position is NaN"),
            std::string::npos);
  const fs::path obj = file("inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_NE(error_of([&] { load_mesh(obj); }).find(obj.string() + ":"), std::string::npos);
}

TEST_F(MeshFiles, EveryTruncationOfABinaryPlyIsRefused) {
  // assimp's own reader crashes on these; every cut must give an error naming the file.
  const std::string whole = tetra_binary_ply(false);
  for (std::size_t n = 0; n < whole.size(); ++n) {
    const fs::path p = file("cut.ply", whole.substr(0, n));
    const std::string e = error_of([&] { load_mesh(p); });
    EXPECT_EQ(e.rfind(p.string() + ":", 0), 0u) << "cut at " << n << ": " << e;
  }
}

TEST_F(MeshFiles, TruncatedTextMeshesAreRefusedWithTheLine) {
  std::string ply = tetra_ascii_ply();
  ply.resize(ply.rfind("3 "));  // the last face is missing
  const fs::path p = file("cut.ply", ply);
  EXPECT_NE(error_of([&] { load_mesh(p); }).find(p.string() + ":17: truncated"), std::string::npos);
  const fs::path off = file("cut.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  EXPECT_NE(error_of([&] { load_mesh(off); }).find("face 2 of 2"), std::string::npos);
}

TEST_F(MeshFiles, GarbageEmptyAndOutOfRangeFilesAreRefused) {
  for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
           {"garbage.ply", "this is not a mesh\n"},
           {"garbage.obj", "\x01\x02\x03 not an obj"},
           {"empty.obj", ""},
           {"lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n"},
           {"badindex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"},
           {"badindex.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"},
           {"badindex.ply",
            std::regex_replace(tetra_ascii_ply(), std::regex("3 1 2 3"), "3 1 2 9")},
           {"badtype.ply", std::regex_replace(tetra_ascii_ply(), std::regex("float x"), "quad x")},
           {"mesh.stl", "solid x\nendsolid x\n"}}) {
    const fs::path p = file(name, text);
    const std::string e = error_of([&] { load_mesh(p); });
    EXPECT_EQ(e.rfind(p.string() + ":", 0), 0u) << name << ": " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << name << ": one line";
  }
  const std::string missing = error_of([&] { load_mesh(dir_ / "nope.ply"); });
  EXPECT_NE(missing.find("nope.ply"), std::string::npos);
}

// The shared real meshes: triangle counts as their PLY headers declare them.
std::uint64_t declared_faces(const fs::path& ply) {
  std::ifstream in(ply, std::ios::binary);
  for (std::string line; std::getline(in, line) && line.rfind("end_header", 0) != 0;) {
    if (line.rfind("element face ", 0) == 0) return std::stoull(line.substr(13));
  }
  return 0;
}

TEST(SharedAssets, BunnyAndTeapotHaveTheirDeclaredTriangles) {
  const fs::path dir = fs::path(AOSUITE_SOURCE_DIR) / ".." / "shared" / "assets";
  if (!fs::is_directory(dir)) GTEST_SKIP() << dir << " is absent (only some machines have it)";
  for (const char* name : {"bun_zipper.ply", "utah_teapot_992.ply"}) {
    const std::uint64_t faces = declared_faces(dir / name);
    ASSERT_GT(faces, 0u) << name;
    const Mesh m = load_mesh(dir / name);
    EXPECT_EQ(m.triangles.size(), faces) << name;
    expect_unit_normals(m);
  }
}

class SceneFiles : public ::testing::Test {
 protected:
  fs::path scene(std::string_view toml, const std::string& name = "s.toml") {
    return write(dir_ / name, toml);
  }
  // The error loading `toml` gives, checked to start with "<file>:<line>:".
  std::string error(std::string_view toml, int line) {
    const fs::path p = scene(toml);
    const std::string e = error_of([&] { load_scene_file(p); });
    EXPECT_EQ(e.rfind(fmt::format("{}:{}:", p.string(), line), 0), 0u) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    return e;
  }
  test::TempDir dir_;
};

constexpr std::string_view kView = "[[views]]\nname = \"v\"\neye = [0, 1, 5]\ntarget = [0, 0, 0]\n";

TEST_F(SceneFiles, PrimitivesViewsAndDefaults) {
  const Scene s = load_scene_file(scene(fmt::format(R"(name = "demo"
[[meshes]]
plane = 10
colour = [0.5, 0.6, 0.7]
[[meshes]]
box = {{ min = [-1, 0, -1], max = [1, 2, 1] }}
[[meshes]]
sphere = {{ centre = [3, 1, 0], radius = 1, segments = 8 }}
[[meshes]]
quad = {{ corner = [0, 0, 0], edge_u = [1, 0, 0], edge_v = [0, 1, 0] }}
{}[[views]]
name = "top"
eye = [0, 10, 0]
target = [0, 0, 0]
up = [0, 0, -1]
fovy_degrees = 45
near = 0.5
)",
                                                    kView)));
  EXPECT_EQ(s.name, "demo");
  ASSERT_EQ(s.meshes.size(), 4u);
  EXPECT_EQ(s.meshes[0].colour, glm::vec3(0.5f, 0.6f, 0.7f));
  expect_near(bounds(s.meshes[0]).first, {-5, 0, -5});
  expect_near(bounds(s.meshes[1]).second, {1, 2, 1});
  expect_near(bounds(s.meshes[2]).first, {2, 0, -1});
  EXPECT_EQ(s.meshes[2].triangles.size(), 2u * 4 * 8);  // segments 8: 4 rings of 8 quads
  ASSERT_EQ(s.views.size(), 2u);
  EXPECT_EQ(s.views[0].name, "v");
  EXPECT_EQ(s.views[0].fovy_degrees, View{}.fovy_degrees);
  EXPECT_EQ(s.views[1].up, glm::vec3(0, 0, -1));
  EXPECT_EQ(s.views[1].fovy_degrees, 45.0f);
  EXPECT_EQ(s.views[1].near, 0.5f);
}

TEST_F(SceneFiles, MeshFilesAreFoundNextToTheSceneFile) {
  write(dir_ / "meshes" / "tetra.ply", tetra_ascii_ply());
  const fs::path toml = scene(fmt::format("[[meshes]]\nfile = \"../meshes/tetra.ply\"\n{}", kView),
                              "scenes/rel.toml");
  const Scene s = load_scene(toml.string());  // the working directory is elsewhere
  EXPECT_EQ(s.name, "rel");                   // no name: the file's stem
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].triangles.size(), 4u);
}

TEST_F(SceneFiles, PlacementFitsRotatesAndGroundsMeshes) {
  // A tetrahedron 1 unit on each axis, fitted to 4: longest side 4, centred on the origin,
  // then stood on the ground and moved.
  write(dir_ / "tetra.ply", tetra_ascii_ply());
  const Scene s = load_scene_file(scene(fmt::format(R"([[meshes]]
file = "tetra.ply"
fit = 4
on_ground = true
translate = [10, 1, 0]
[[meshes]]
file = "tetra.ply"
scale = [2, 3, 4]
rotate_degrees = [0, 90, 0]
{})",
                                                    kView)));
  const auto [lo, hi] = bounds(s.meshes[0]);
  expect_near(lo, {8, 1, -2});
  expect_near(hi, {12, 5, 2});
  // Scaled to (2, 3, 4) on the axes, then +x turns to -z and +z to +x about y.
  const auto [lo2, hi2] = bounds(s.meshes[1]);
  expect_near(lo2, {0, 0, -2});
  expect_near(hi2, {4, 3, 0});
  expect_unit_normals(s.meshes[1]);
}

TEST_F(SceneFiles, MistakesAreReportedWithTheirLine) {
  const std::string box = "[[meshes]]\nbox = { min = [0, 0, 0], max = [1, 1, 1] }\n";
  EXPECT_NE(error("[[meshes]\nplane = 1\n", 1).find("s.toml:1:"), std::string::npos);
  EXPECT_NE(error(box + "colr = [1, 1, 1]\n" + std::string(kView), 3).find("unknown key 'colr'"),
            std::string::npos);
  EXPECT_NE(error(box + "colour = \"red\"\n" + std::string(kView), 3).find("colour must be"),
            std::string::npos);
  EXPECT_NE(error(box + "fit = nan\n" + std::string(kView), 3).find("finite"), std::string::npos);
  EXPECT_NE(error(box + "scale = 0\n" + std::string(kView), 3).find("positive"), std::string::npos);
  EXPECT_NE(error(box, 1).find("missing 'views'"), std::string::npos);
  EXPECT_NE(error("views = []\n" + box, 1).find("must not be empty"), std::string::npos);
  EXPECT_NE(error(box + std::string(kView) + std::string(kView), 7).find("duplicate view name 'v'"),
            std::string::npos);
  EXPECT_NE(error(box + "[[views]]\nname = \"v\"\neye = [0, 1, 5]\n", 3).find("missing 'target'"),
            std::string::npos);
  EXPECT_NE(error(box + "[[views]]\nname = \"v\"\neye = [0, 1, 0]\ntarget = [0, 0, 0]\n", 3)
                .find("parallel"),
            std::string::npos);
  EXPECT_NE(error(box + "[[views]]\nname = \"a/b\"\neye = [0, 1, 5]\ntarget = [0, 0, 0]\n", 4)
                .find("name"),
            std::string::npos);
  EXPECT_NE(error("[[meshes]]\nplane = 1\nsphere = { centre = [0, 0, 0], radius = 1 }\n" +
                      std::string(kView),
                  1)
                .find("exactly one"),
            std::string::npos);
  EXPECT_NE(error("[[meshes]]\nbox = { min = [0, 0], max = [1, 1, 1] }\n" + std::string(kView), 2)
                .find("3 numbers"),
            std::string::npos);
}

TEST_F(SceneFiles, UnreadableMeshesNameBothFiles) {
  const std::string e = error("[[meshes]]\nfile = \"missing.obj\"\n" + std::string(kView), 2);
  EXPECT_NE(e.find("missing.obj"), std::string::npos) << e;
  write(dir_ / "lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n");
  EXPECT_NE(
      error("[[meshes]]\nfile = \"lines.obj\"\n" + std::string(kView), 2).find("no triangles"),
      std::string::npos);
}

TEST(BuiltinScenes, NamesFilesAndTheDragon) {
  EXPECT_EQ(load_scene("corner").name, "corner");
  EXPECT_THROW(load_scene("no-such-scene"), std::invalid_argument);
  const auto names = builtin_scene_names();
  EXPECT_EQ(std::count(names.begin(), names.end(), "dragon"), 0);  // needs a download
  EXPECT_EQ(downloadable_scene_names(), std::vector<std::string>{"dragon"});
  EXPECT_EQ(builtin_scene_views("dragon").size(), 2u);
  EXPECT_EQ(builtin_scene_views("village").size(), 2u);

  test::TempDir empty;
  const char* before = std::getenv("AOSUITE_ASSETS");
  const std::string saved = before ? before : "";
  setenv("AOSUITE_ASSETS", empty.path().c_str(), 1);
  EXPECT_EQ(downloadable_scene_file("dragon").parent_path(), empty.path());
  const std::string e = error_of([] { builtin_scene("dragon"); });
  EXPECT_NE(e.find("scripts/fetch_dragon.sh"), std::string::npos) << e;
  before ? setenv("AOSUITE_ASSETS", saved.c_str(), 1) : unsetenv("AOSUITE_ASSETS");
}

TEST(BuiltinScenes, DragonStandsOnTheGroundWhenFetched) {
  const fs::path file = downloadable_scene_file("dragon");
  if (!fs::exists(file)) GTEST_SKIP() << file << " not fetched (scripts/fetch_dragon.sh)";
  const Scene s = builtin_scene("dragon");
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[1].triangles.size(), declared_faces(file));
  const auto [lo, hi] = bounds(s.meshes[1]);
  EXPECT_NEAR(lo.y, 0, 1e-4);
  EXPECT_NEAR(std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}), 5, 1e-3);
}

TEST(ExampleScenes, LoadWhenTheSharedAssetsArePresent) {
  if (!fs::is_directory(fs::path(AOSUITE_SOURCE_DIR) / ".." / "shared" / "assets")) {
    GTEST_SKIP() << "../shared/assets is absent";
  }
  for (const auto& entry :
       fs::directory_iterator(fs::path(AOSUITE_SOURCE_DIR) / "suites" / "scenes")) {
    if (entry.path().extension() != ".toml") continue;
    const Scene s = load_scene_file(entry.path());
    EXPECT_GE(s.meshes.size(), 2u) << entry.path();
    EXPECT_GE(s.views.size(), 2u) << entry.path();
  }
}

}  // namespace
}  // namespace aosuite::renderer

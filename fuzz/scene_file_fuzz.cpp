// Scene files (renderer/scene_file.hpp) on any bytes: a file is refused with an escaped
// one-line FileError, or gives a scene the renderer accepts, every mesh and view of it.
// Beside the scene lie one small mesh of each format (tri.ply, tri.obj, tri.off) for `file`.
#include "common/file_io.hpp"
#include "fuzz/renderable.hpp"
#include "renderer/scene/scene_file.hpp"
#include "renderer/scene/view_check.hpp"

namespace fuzz = aosuite::fuzz;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // A scene's triangle limit, low enough that a sphere of many segments stays fast here.
  ::setenv("AOSUITE_MAX_TRIANGLES", "200000", 1);
  fuzz::write_file(fuzz::scratch() / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  fuzz::write_file(fuzz::scratch() / "tri.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  fuzz::write_file(fuzz::scratch() / "tri.ply",
                   "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                   "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path file = fuzz::scratch() / "scene.toml";
  fuzz::write_file(file, fuzz::as_text(data, size));
  try {
    const aosuite::renderer::Scene scene = aosuite::renderer::load_scene_file(file);
    for (const auto& mesh : scene.meshes) fuzz::expect_renderable(mesh);
    for (const auto& view : scene.views) {
      if (aosuite::renderer::view_problem(view)) fuzz::fail("a view the renderer refuses");
    }
  } catch (const aosuite::FileError& e) {
    fuzz::expect_printable(e.what());
  }
  return 0;
}

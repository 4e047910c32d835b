// Mesh files (renderer/mesh_io.hpp: the structure checks, then assimp) on any bytes: a file is
// refused with an escaped one-line FileError, or gives a mesh the renderer can draw.
// The format is the one the bytes claim (PLY's and OFF's magic, STL's "solid" or its binary
// size of 84 + 50 bytes a triangle), else OBJ, which has none.
#include "common/file_io.hpp"
#include "fuzz/renderable.hpp"
#include "renderer/scene/mesh_io.hpp"

namespace {

namespace fuzz = aosuite::fuzz;

// OFF and its variants: [ST][C][N][4][n]OFF as the first word.
bool claims_off(std::string_view text) {
  const std::string_view word = text.substr(0, text.find_first_of(" \t\r\n"));
  return word.size() <= 8 && word.ends_with("OFF");
}

bool claims_stl(std::string_view bytes) {
  if (bytes.starts_with("solid")) return true;
  if (bytes.size() < 84) return false;
  std::uint32_t count = 0;
  for (int i = 3; i >= 0; --i) count = count << 8 | static_cast<unsigned char>(bytes[80 + i]);
  return bytes.size() == 84 + std::uint64_t{50} * count;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = fuzz::as_text(data, size);
  const char* ext = text.starts_with("ply") ? "mesh.ply"
                    : claims_off(text)      ? "mesh.off"
                    : claims_stl(text)      ? "mesh.stl"
                                            : "mesh.obj";
  const std::filesystem::path file = fuzz::scratch() / ext;
  fuzz::write_file(file, text);
  try {
    fuzz::expect_renderable(aosuite::renderer::load_mesh(file));
  } catch (const aosuite::FileError& e) {
    fuzz::expect_printable(e.what());
  }
  return 0;
}

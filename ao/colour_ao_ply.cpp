#include "ao/colour_ao_ply.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "image/image_io.hpp"

namespace aosuite::ao {

namespace fs = std::filesystem;
namespace rd = aosuite::renderer;

void write_colour_ao(const fs::path& path, const rd::PmiObject& object,
                     const rd::PmiChannel& channel) {
  const std::vector<glm::vec3> polygon = rd::polygon_colour_visibility(channel);
  std::vector<float> per_vertex[3];
  for (int a = 0; a < 3; ++a) {
    std::vector<float> one(polygon.size());
    for (std::size_t o = 0; o < one.size(); ++o) one[o] = polygon[o][a];
    per_vertex[a] = rd::vertex_visibility(object, one);
  }
  std::string ply = fmt::format(
      "ply\nformat ascii 1.0\ncomment colour ambient occlusion (PMI, eq. 12)\n"
      "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face {}\nproperty list uchar int vertex_indices\nend_header\n",
      object.positions.size(), object.triangles.size());
  auto byte = [](float x) {
    return static_cast<int>(std::lround(std::clamp(x, 0.0f, 1.0f) * 255));
  };
  for (std::size_t i = 0; i < object.positions.size(); ++i) {
    const glm::vec3 p = object.positions[i];
    ply += fmt::format("{} {} {} {} {} {}\n", p.x, p.y, p.z, byte(per_vertex[0][i]),
                       byte(per_vertex[1][i]), byte(per_vertex[2][i]));
  }
  for (const glm::uvec3& t : object.triangles) ply += fmt::format("3 {} {} {}\n", t.x, t.y, t.z);
  write_text(path, ply);
}

}  // namespace aosuite::ao

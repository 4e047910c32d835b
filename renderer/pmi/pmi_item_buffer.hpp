// PMI's item buffer: the object drawn with each polygon's ID into an R32UI target, then a
// compute pass that histograms the IDs into a per-polygon counter buffer with atomic adds, so
// only one counter per polygon comes back per viewpoint, never a frame.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/gl/gl_objects.hpp"
#include "renderer/pmi/pmi_object.hpp"

namespace aosuite::renderer {

class ItemBuffer {
 public:
  // Keeps a reference to `object`.
  ItemBuffer(const PmiObject& object, int width, int height);
  // a_o(eye): the pixels of each polygon seen from `eye`, looking at the object's centre.
  const std::vector<std::uint32_t>& count(glm::vec3 eye);

 private:
  const PmiObject& object_;
  int width_, height_;
  Program draw_, histogram_;
  IndexedMesh mesh_;
  Buffer counters_;
  Texture ids_, depth_;
  Framebuffer fb_;
  std::vector<std::uint32_t> counts_;
};

}  // namespace aosuite::renderer

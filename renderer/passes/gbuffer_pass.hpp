// Pass 1: rasterise the scene into the G-buffer (linear depth, view normals, albedo).
#pragma once

#include "renderer/frame.hpp"

namespace aosuite::renderer {

// The scene's triangles uploaded once, in world space, interleaved position/normal/colour.
class GpuScene {
 public:
  explicit GpuScene(const Scene& scene);
  void draw() const { mesh_.draw(); }
  bool empty() const { return mesh_.empty(); }

 private:
  IndexedMesh mesh_;
};

class GBufferPass {
 public:
  GBufferPass();
  void run(const GpuScene& scene, const Camera& camera, const GBuffer& target) const;

 private:
  Program program_;
};

}  // namespace aosuite::renderer

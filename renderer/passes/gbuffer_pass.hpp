// Pass 1: rasterise the scene into the G-buffer (linear depth, view normals, albedo).
#pragma once

#include <vector>

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

// XeGTAO's G-buffer: the scene rasterised into the depth buffer alone (no fragment shader,
// no colour targets), then one compute dispatch that writes linear depth and normals
// reconstructed from depth (depth_gbuffer.comp) into `target`; albedo is left as it was.
// Issue 44 asks whether this is cheaper than GBufferPass on a GPU whose fragment stage is
// slow, and as accurate: render_bench's BM_GBuffer/depth_only measures both.
class DepthGBufferPass {
 public:
  DepthGBufferPass();
  // Times the rasterisation ("gbuffer") and the reconstruction ("gbuffer_normals") apart.
  std::vector<PassTimer> run(const GpuScene& scene, const Camera& camera, const GBuffer& target);

 private:
  Program raster_;
  int rows_;  // pixels an invocation of depth_gbuffer.comp shades (light_pass_rows)
  Program reconstruct_;
  Framebuffer depth_only_;
  GLuint framebuffer_zbuffer_ = 0;  // the depth texture depth_only_ was made for
};

}  // namespace aosuite::renderer

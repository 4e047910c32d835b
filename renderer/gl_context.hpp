// The GL context behind a small interface, so an EGL (GPU) backend can replace OSMesa
// without touching the passes. Passes render into their own framebuffer objects only.
#pragma once

#include <memory>
#include <string>

namespace aosuite::renderer {

class GlContext {
 public:
  virtual ~GlContext() = default;
  // "vendor | renderer | version", for golden variants keyed by driver.
  virtual std::string description() const = 0;

 protected:
  // Core profile draws nothing without a vertex array, and vertex arrays are not shared
  // between contexts: each context binds its own empty one once, for the full-screen passes.
  static void bind_empty_vertex_array();
};

// An offscreen OpenGL 4.5 core context from Mesa (llvmpipe: no GPU or display needed).
// Throws std::runtime_error when none can be made.
std::unique_ptr<GlContext> make_osmesa_context();

}  // namespace aosuite::renderer

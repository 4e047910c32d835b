#include "renderer/gl_context.hpp"

#include "renderer/gl.hpp"
// osmesa.h after gl.h: it needs GL's types.
#include <GL/osmesa.h>

#include <stdexcept>
#include <vector>

namespace aosuite::renderer {
namespace {

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           0,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           4,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           5,
                           0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_) throw std::runtime_error("OSMesa: cannot create an OpenGL 4.5 core context");
    // The default framebuffer is never drawn to; a 1x1 one makes the context current.
    if (!OSMesaMakeCurrent(ctx_, &pixel_, GL_UNSIGNED_BYTE, 1, 1)) {
      OSMesaDestroyContext(ctx_);
      throw std::runtime_error("OSMesa: cannot make the context current");
    }
    bind_empty_vertex_array();
  }
  ~OsMesaContext() override { OSMesaDestroyContext(ctx_); }

  std::string description() const override {
    auto str = [](GLenum e) { return std::string(reinterpret_cast<const char*>(glGetString(e))); };
    return str(GL_VENDOR) + " | " + str(GL_RENDERER) + " | " + str(GL_VERSION);
  }

 private:
  OSMesaContext ctx_ = nullptr;
  unsigned int pixel_ = 0;
};

}  // namespace

void GlContext::bind_empty_vertex_array() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  glBindVertexArray(id);
}

std::unique_ptr<GlContext> make_osmesa_context() { return std::make_unique<OsMesaContext>(); }

}  // namespace aosuite::renderer

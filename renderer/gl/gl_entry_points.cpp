#include <mutex>
#include <stdexcept>
#include <string>

#include "renderer/gl/gl.hpp"

namespace aosuite::renderer {

#define AOSUITE_GL_DEFINE(type, name) type name = nullptr;
AOSUITE_GL_ENTRY_POINTS(AOSUITE_GL_DEFINE)
#undef AOSUITE_GL_DEFINE

void load_gl_entry_points(GlGetProcAddress get_proc) {
  // One table per process: every context of a process comes from the same backend, whose
  // entry points serve all its contexts (EGL's and OSMesa's both dispatch on the current
  // context), so the table is filled once and never rewritten under a rendering thread.
  static std::mutex mutex;
  static GlGetProcAddress loaded_with = nullptr;
  const std::lock_guard lock(mutex);
  if (loaded_with == get_proc) return;
  if (loaded_with) {
    throw std::runtime_error("this process already renders through another GL backend");
  }
#define AOSUITE_GL_LOAD(type, name)                                     \
  name = reinterpret_cast<type>(get_proc(#name));                       \
  if (!name) {                                                          \
    throw std::runtime_error(std::string("the driver lacks ") + #name + \
                             " (OpenGL 4.5 core is required)");         \
  }
  AOSUITE_GL_ENTRY_POINTS(AOSUITE_GL_LOAD)
#undef AOSUITE_GL_LOAD
  loaded_with = get_proc;
}

}  // namespace aosuite::renderer

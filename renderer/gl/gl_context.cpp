#include "renderer/gl/gl_context.hpp"

#include <cstdlib>
#include <mutex>
#include <stdexcept>

#include "renderer/gl/gl.hpp"

namespace aosuite::renderer {
namespace {

std::mutex choice_mutex;
std::optional<GlBackend> backend_flag;
std::optional<int> device_flag;

}  // namespace

GlBackend parse_gl_backend(const std::string& name) {
  if (name == "auto") return GlBackend::kAuto;
  if (name == "egl") return GlBackend::kEgl;
  if (name == "osmesa") return GlBackend::kOsMesa;
  throw std::invalid_argument("unknown GL backend '" + name + "' (auto, egl, osmesa)");
}

GlChoice gl_choice() {
  const std::lock_guard lock(choice_mutex);
  GlChoice c;
  if (backend_flag) {
    c.backend = *backend_flag;
  } else if (const char* name = std::getenv("AOSUITE_GL"); name && *name) {
    try {
      c.backend = parse_gl_backend(name);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("AOSUITE_GL: ") + e.what());
    }
  }
  if (device_flag) {
    c.device = device_flag;
  } else if (const char* index = std::getenv("AOSUITE_GL_DEVICE"); index && *index) {
    char* end = nullptr;
    const long n = std::strtol(index, &end, 10);
    if (*end != '\0' || n < 0 || n > 1024) {
      throw std::invalid_argument(std::string("AOSUITE_GL_DEVICE: '") + index +
                                  "' is not a device index (aosuite gl-info lists them)");
    }
    c.device = static_cast<int>(n);
  }
  return c;
}

void set_gl_backend(GlBackend backend) {
  const std::lock_guard lock(choice_mutex);
  backend_flag = backend;
}

void set_gl_device(int device) {
  const std::lock_guard lock(choice_mutex);
  device_flag = device;
}

void GlContext::adopt_current(void* (*get_proc)(const char*), std::string source) {
  GlProbe probe;
  detail::describe_current(get_proc, probe);
  if (!probe.meets_requirement) {
    throw std::runtime_error(source + " gives OpenGL " + probe.version +
                             "; aosuite needs 4.5 core");
  }
  load_gl_entry_points(get_proc);
  description_ = probe.vendor + " | " + probe.renderer + " | " + probe.version;
  source_ = std::move(source);
  GLuint vertex_array = 0;
  glCreateVertexArrays(1, &vertex_array);
  glBindVertexArray(vertex_array);
}

bool software_renderer(std::string_view renderer) {
  for (const std::string_view name : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
    if (renderer.find(name) != std::string_view::npos) return true;
  return false;
}

void detail::describe_current(void* (*get_proc)(const char*), GlProbe& probe) {
  // Local pointers, not the shared table: gl-info probes backends the process may not render
  // with.
  const auto get_string = reinterpret_cast<PFNGLGETSTRINGPROC>(get_proc("glGetString"));
  const auto get_integer = reinterpret_cast<PFNGLGETINTEGERVPROC>(get_proc("glGetIntegerv"));
  if (!get_string || !get_integer) throw std::runtime_error("the driver lacks glGetString");
  auto str = [&](GLenum e) {
    const GLubyte* s = get_string(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  probe.vendor = str(GL_VENDOR), probe.renderer = str(GL_RENDERER), probe.version = str(GL_VERSION);
  GLint major = 0, minor = 0, profile = 0;
  get_integer(GL_MAJOR_VERSION, &major);
  get_integer(GL_MINOR_VERSION, &minor);
  get_integer(GL_CONTEXT_PROFILE_MASK, &profile);
  probe.meets_requirement =
      (major > 4 || (major == 4 && minor >= 5)) && (profile & GL_CONTEXT_CORE_PROFILE_BIT);
}

std::unique_ptr<GlContext> make_gl_context(const GlChoice& choice) {
  if (choice.backend == GlBackend::kOsMesa) {
    if (choice.device) {
      throw std::runtime_error("--gl-device selects an EGL device; OSMesa has none");
    }
    if (!osmesa_built()) {
      throw std::runtime_error(
          "this build has no OSMesa backend (use --gl egl; aosuite gl-info "
          "lists the devices)");
    }
    return detail::make_osmesa_context();
  }
  if (choice.backend == GlBackend::kEgl || choice.device || !osmesa_built()) {
    return detail::make_egl_context(choice.device);
  }
  try {
    return detail::make_egl_context(std::nullopt);
  } catch (const std::runtime_error& egl_error) {
    try {
      return detail::make_osmesa_context();
    } catch (const std::runtime_error& osmesa_error) {
      throw std::runtime_error(std::string(egl_error.what()) + "; " + osmesa_error.what());
    }
  }
}

std::vector<GlProbe> probe_gl_backends() {
  std::vector<GlProbe> out = detail::probe_egl();
  if (osmesa_built()) out.push_back(detail::probe_osmesa());
  return out;
}

}  // namespace aosuite::renderer

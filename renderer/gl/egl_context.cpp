// The EGL backend: desktop OpenGL with no window system, on a GPU (NVIDIA's and Mesa's drivers
// expose their devices through EGL_EXT_device_enumeration + EGL_EXT_platform_device) or on
// Mesa's software device (llvmpipe), with Mesa's surfaceless platform as the fallback.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "renderer/gl/gl_context.hpp"

namespace aosuite::renderer {
namespace {

bool has_extension(const char* list, std::string_view name) {
  const std::string_view all = list ? list : "";
  for (std::size_t at = all.find(name); at != std::string_view::npos; at = all.find(name, at + 1)) {
    const std::size_t end = at + name.size();
    if ((at == 0 || all[at - 1] == ' ') && (end == all.size() || all[end] == ' ')) return true;
  }
  return false;
}

std::string egl_error() {
  const EGLint code = eglGetError();
  switch (code) {
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return "EGL error " + std::to_string(code);
  }
}

void* egl_proc(const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

// The client extensions' entry points; null where the EGL library lacks them.
struct EglClientApi {
  PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;
  bool surfaceless = false;  // EGL_MESA_platform_surfaceless
};

const EglClientApi& client_api() {
  static const EglClientApi api = [] {
    EglClientApi a;
    const char* ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (has_extension(ext, "EGL_EXT_platform_base")) {
      a.get_platform_display =
          reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(egl_proc("eglGetPlatformDisplayEXT"));
    }
    if (has_extension(ext, "EGL_EXT_device_enumeration") &&
        has_extension(ext, "EGL_EXT_platform_device")) {
      a.query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(egl_proc("eglQueryDevicesEXT"));
      a.query_device_string =
          reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(egl_proc("eglQueryDeviceStringEXT"));
    }
    a.surfaceless = has_extension(ext, "EGL_MESA_platform_surfaceless");
    return a;
  }();
  return api;
}

struct EglDevice {
  EGLDeviceEXT handle;
  bool hardware;
  std::string source;  // "EGL device 0 (/dev/dri/card0)"
};

std::vector<EglDevice> egl_devices() {
  const EglClientApi& api = client_api();
  if (!api.query_devices || !api.get_platform_display) return {};
  EGLint count = 0;
  if (!api.query_devices(0, nullptr, &count) || count <= 0) return {};
  std::vector<EGLDeviceEXT> handles(static_cast<std::size_t>(count));
  if (!api.query_devices(count, handles.data(), &count)) return {};
  std::vector<EglDevice> out;
  for (EGLint i = 0; i < count; ++i) {
    EGLDeviceEXT d = handles[static_cast<std::size_t>(i)];
    const char* ext = api.query_device_string(d, EGL_EXTENSIONS);
    const bool software = has_extension(ext, "EGL_MESA_device_software");
    const char* file = has_extension(ext, "EGL_EXT_device_drm")
                           ? api.query_device_string(d, EGL_DRM_DEVICE_FILE_EXT)
                           : nullptr;
    const std::string what = software ? "software" : file ? file : "hardware";
    out.push_back({d, !software, "EGL device " + std::to_string(i) + " (" + what + ")"});
  }
  return out;
}

// An initialised display; EGL displays are process-wide and initialising one twice is a no-op,
// so contexts on several threads share it. Never terminated: that would end every context.
EGLDisplay open_display(EGLenum platform, void* native, const std::string& source) {
  EGLDisplay display = client_api().get_platform_display(platform, native, nullptr);
  if (display == EGL_NO_DISPLAY) throw std::runtime_error(source + ": no display");
  if (!eglInitialize(display, nullptr, nullptr)) {
    throw std::runtime_error(source + ": eglInitialize failed (" + egl_error() + ")");
  }
  return display;
}

// An OpenGL 4.5 core context with no window, current on the calling thread while it lives.
// Where the driver lacks EGL_KHR_no_config_context or EGL_KHR_surfaceless_context, a config
// and a 1x1 pbuffer stand in; nothing is ever drawn to the default framebuffer.
class CurrentEglContext {
 public:
  CurrentEglContext(EGLDisplay display, const std::string& source) : display_(display) {
    const char* ext = eglQueryString(display, EGL_EXTENSIONS);
    if (!eglBindAPI(EGL_OPENGL_API)) {  // per thread
      throw std::runtime_error(source + ": no desktop OpenGL (" + egl_error() + ")");
    }
    EGLConfig config = EGL_NO_CONFIG_KHR;
    const bool surfaceless = has_extension(ext, "EGL_KHR_surfaceless_context");
    if (!has_extension(ext, "EGL_KHR_no_config_context") || !surfaceless) {
      const EGLint want[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                             EGL_NONE};
      EGLint n = 0;
      if (!eglChooseConfig(display, want, &config, 1, &n) || n < 1) {
        throw std::runtime_error(source + ": no OpenGL config (" + egl_error() + ")");
      }
    }
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              4,
                              EGL_CONTEXT_MINOR_VERSION,
                              5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    context_ = eglCreateContext(display, config, EGL_NO_CONTEXT, attribs);
    if (context_ == EGL_NO_CONTEXT) {
      throw std::runtime_error(source + ": no OpenGL 4.5 core context (" + egl_error() + ")");
    }
    if (!surfaceless) {
      const EGLint size[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
      surface_ = eglCreatePbufferSurface(display, config, size);
    }
    if (!eglMakeCurrent(display, surface_, surface_, context_)) {
      const std::string why = egl_error();
      release();
      throw std::runtime_error(source + ": cannot make the context current (" + why + ")");
    }
  }
  ~CurrentEglContext() { release(); }
  CurrentEglContext(const CurrentEglContext&) = delete;
  CurrentEglContext& operator=(const CurrentEglContext&) = delete;

 private:
  void release() {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    eglDestroyContext(display_, context_);
    eglReleaseThread();
  }

  EGLDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
};

class EglContext final : public GlContext {
 public:
  EglContext(EGLDisplay display, const std::string& source) : context_(display, source) {
    adopt_current(egl_proc, source);
  }

 private:
  CurrentEglContext context_;
};

const std::string kSurfaceless = "EGL surfaceless";
// What GLVND's libEGL says, in effect, when no vendor library (driver) is installed.
const char* const kNoPlatform = "EGL: no EGL driver found (the EGL library offers no platforms)";

EGLDisplay device_display(const EglDevice& d) {
  return open_display(EGL_PLATFORM_DEVICE_EXT, d.handle, d.source);
}

EGLDisplay surfaceless_display() {
  return open_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, kSurfaceless);
}

std::string list_devices(const std::vector<EglDevice>& devices) {
  if (devices.empty()) return "no EGL devices";
  std::string s;
  for (const EglDevice& d : devices) s += (s.empty() ? "" : ", ") + d.source;
  return s;
}

}  // namespace

std::unique_ptr<GlContext> detail::make_egl_context(std::optional<int> device) {
  if (!client_api().get_platform_display) throw std::runtime_error(kNoPlatform);
  const std::vector<EglDevice> devices = egl_devices();
  if (device) {
    if (*device < 0 || *device >= static_cast<int>(devices.size())) {
      throw std::runtime_error("EGL device " + std::to_string(*device) +
                               " does not exist (this machine has " + list_devices(devices) + ")");
    }
    const EglDevice& d = devices[static_cast<std::size_t>(*device)];
    return std::make_unique<EglContext>(device_display(d), d.source);
  }
  // A GPU first, then Mesa's software device, then the surfaceless platform.
  std::string tried;
  for (const bool hardware : {true, false}) {
    for (const EglDevice& d : devices) {
      if (d.hardware != hardware) continue;
      try {
        return std::make_unique<EglContext>(device_display(d), d.source);
      } catch (const std::runtime_error& e) {
        tried += std::string(tried.empty() ? "" : "; ") + e.what();
      }
    }
  }
  if (client_api().surfaceless) {
    try {
      return std::make_unique<EglContext>(surfaceless_display(), kSurfaceless);
    } catch (const std::runtime_error& e) {
      tried += std::string(tried.empty() ? "" : "; ") + e.what();
    }
  }
  throw std::runtime_error("EGL: no OpenGL 4.5 core context (" +
                           (tried.empty() ? list_devices(devices) : tried) + ")");
}

std::vector<GlProbe> detail::probe_egl() {
  std::vector<GlProbe> out;
  auto probe = [&](GlProbe p, auto display) {
    try {
      const CurrentEglContext context(display(), p.source);
      describe_current(egl_proc, p);
      // The surfaceless platform names no device: its renderer says what draws (a GPU's driver
      // may offer it where no EGL device is listed, as NVIDIA's does in a container).
      if (p.device < 0) p.hardware = !software_renderer(p.renderer);
    } catch (const std::runtime_error& e) {
      p.error = e.what();
    }
    out.push_back(std::move(p));
  };
  if (!client_api().get_platform_display) {
    out.push_back({"EGL", "egl", -1, false, {}, {}, {}, false, kNoPlatform});
    return out;
  }
  const std::vector<EglDevice> devices = egl_devices();
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const EglDevice& d = devices[i];
    probe({d.source, "egl", static_cast<int>(i), d.hardware, {}, {}, {}, false, {}},
          [&] { return device_display(d); });
  }
  if (client_api().surfaceless) {
    probe({kSurfaceless, "egl", -1, false, {}, {}, {}, false, {}}, surfaceless_display);
  }
  return out;
}

}  // namespace aosuite::renderer

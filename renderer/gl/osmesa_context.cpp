// The OSMesa backend: Mesa's off-screen llvmpipe, for Mesa < 25.1 (which removed OSMesa).
// libOSMesa is opened only when this backend is chosen: it links LLVM, which a process
// rendering through EGL on a GPU should not pay for, and its exported gl* symbols stay local.
#include <GL/osmesa.h>  // GL/gl.h's types; the entry points come from OSMesaGetProcAddress
#include <dlfcn.h>

#include <mutex>
#include <stdexcept>
#include <string>

#include "renderer/gl/gl_context.hpp"

namespace aosuite::renderer {
namespace {

struct OsMesaApi {
  decltype(&OSMesaCreateContextAttribs) create = nullptr;
  decltype(&OSMesaMakeCurrent) make_current = nullptr;
  decltype(&OSMesaDestroyContext) destroy = nullptr;
  decltype(&OSMesaGetProcAddress) get_proc = nullptr;
};

// Throws std::runtime_error when libOSMesa cannot be opened.
const OsMesaApi& osmesa_api() {
  static std::once_flag once;
  static OsMesaApi api;
  static std::string error;
  std::call_once(once, [] {
    void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
      error = std::string("OSMesa: cannot open libOSMesa.so.8: ") + dlerror();
      return;
    }
    auto sym = [&](const char* name) { return dlsym(lib, name); };
    api.create = reinterpret_cast<decltype(api.create)>(sym("OSMesaCreateContextAttribs"));
    api.make_current = reinterpret_cast<decltype(api.make_current)>(sym("OSMesaMakeCurrent"));
    api.destroy = reinterpret_cast<decltype(api.destroy)>(sym("OSMesaDestroyContext"));
    api.get_proc = reinterpret_cast<decltype(api.get_proc)>(sym("OSMesaGetProcAddress"));
    if (!api.create || !api.make_current || !api.destroy || !api.get_proc) {
      error = "OSMesa: libOSMesa.so.8 lacks OSMesaCreateContextAttribs";
    }
  });
  if (!error.empty()) throw std::runtime_error(error);
  return api;
}

void* osmesa_proc(const char* name) { return reinterpret_cast<void*>(osmesa_api().get_proc(name)); }

// An OSMesa context, current on the calling thread while it lives.
class CurrentOsMesaContext {
 public:
  CurrentOsMesaContext() : api_(osmesa_api()) {
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
    ctx_ = api_.create(attribs, nullptr);
    if (!ctx_) throw std::runtime_error("OSMesa: cannot create an OpenGL 4.5 core context");
    // The default framebuffer is never drawn to; a 1x1 one makes the context current.
    if (!api_.make_current(ctx_, &pixel_, GL_UNSIGNED_BYTE, 1, 1)) {
      api_.destroy(ctx_);
      throw std::runtime_error("OSMesa: cannot make the context current");
    }
  }
  ~CurrentOsMesaContext() { api_.destroy(ctx_); }
  CurrentOsMesaContext(const CurrentOsMesaContext&) = delete;
  CurrentOsMesaContext& operator=(const CurrentOsMesaContext&) = delete;

 private:
  const OsMesaApi& api_;
  OSMesaContext ctx_ = nullptr;
  unsigned int pixel_ = 0;
};

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() { adopt_current(osmesa_proc, "OSMesa"); }

 private:
  CurrentOsMesaContext context_;
};

}  // namespace

bool osmesa_built() { return true; }

std::unique_ptr<GlContext> detail::make_osmesa_context() {
  return std::make_unique<OsMesaContext>();
}

GlProbe detail::probe_osmesa() {
  GlProbe probe{"OSMesa", "osmesa", -1, false, {}, {}, {}, false, {}};
  try {
    const CurrentOsMesaContext context;
    describe_current(osmesa_proc, probe);
  } catch (const std::runtime_error& e) {
    probe.error = e.what();
  }
  return probe;
}

}  // namespace aosuite::renderer

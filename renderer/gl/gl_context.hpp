// The GL context behind a small interface: EGL (any GPU, or Mesa's llvmpipe with no display)
// or OSMesa where the build has it. Passes render into their own framebuffer objects only, so
// they never see which backend made the context.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace aosuite::renderer {

enum class GlBackend { kAuto, kEgl, kOsMesa };

// Which backend and device to open: `--gl auto|egl|osmesa` and `--gl-device N`, or the
// AOSUITE_GL and AOSUITE_GL_DEVICE environment variables.
struct GlChoice {
  GlBackend backend = GlBackend::kAuto;
  std::optional<int> device;  // an index into EGL's device list (`aosuite gl-info`)
};
// Throws std::invalid_argument for a name other than auto, egl or osmesa.
GlBackend parse_gl_backend(const std::string& name);
// The choice every Renderer of this process makes its context with: the environment's, with
// what set_gl_backend and set_gl_device (the command-line flags) said over it. Throws
// std::invalid_argument for a malformed variable.
GlChoice gl_choice();
void set_gl_backend(GlBackend backend);
void set_gl_device(int device);

bool osmesa_built();  // whether this build has the OSMesa backend

class GlContext {
 public:
  virtual ~GlContext() = default;
  // "vendor | renderer | version", for golden variants keyed by driver.
  const std::string& description() const { return description_; }
  // Which backend and device, e.g. "EGL device 0 (software)" or "OSMesa".
  const std::string& source() const { return source_; }

 protected:
  GlContext() = default;
  // With the new context current: checks it is OpenGL >= 4.5 core, fills the entry-point
  // table through `get_proc`, and binds an empty vertex array (core profile draws nothing
  // without one, and vertex arrays are not shared between contexts). Throws
  // std::runtime_error naming `source` when the context falls short.
  void adopt_current(void* (*get_proc)(const char*), std::string source);

 private:
  std::string description_, source_;
};

// Makes a context for `choice` and makes it current on the calling thread. `auto` takes EGL
// (a hardware device first, then Mesa's software device, then the surfaceless platform) and
// falls back to OSMesa. Throws std::runtime_error, in one line, naming what was tried and
// which backends and devices exist.
std::unique_ptr<GlContext> make_gl_context(const GlChoice& choice);

// What `aosuite gl-info` lists: every backend and device this process can open.
struct GlProbe {
  std::string source;     // as GlContext::source()
  std::string backend;    // "egl" or "osmesa"
  int device = -1;        // EGL device index; -1 for the surfaceless platform and OSMesa
  bool hardware = false;  // a GPU (not Mesa's software device)
  std::string vendor, renderer, version;
  bool meets_requirement = false;  // OpenGL >= 4.5 core
  std::string error;               // why no context could be made, else empty
};
std::vector<GlProbe> probe_gl_backends();

// Whether a GL_RENDERER string names a software rasteriser (Mesa's llvmpipe, softpipe or swrast,
// SwiftShader): how the surfaceless platform, which names no device, tells a GPU from the CPU.
bool software_renderer(std::string_view renderer);

namespace detail {
// The backends, each in its own file; `device` < 0 picks as `auto` does.
std::unique_ptr<GlContext> make_egl_context(std::optional<int> device);
std::vector<GlProbe> probe_egl();
std::unique_ptr<GlContext> make_osmesa_context();
GlProbe probe_osmesa();
// Reads vendor, renderer, version and the 4.5-core requirement from the current context.
void describe_current(void* (*get_proc)(const char*), GlProbe& probe);
}  // namespace detail

}  // namespace aosuite::renderer

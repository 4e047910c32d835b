// A build without OSMesa (Mesa >= 25.1 removed it): the backend is named, never made.
#include <stdexcept>

#include "renderer/gl/gl_context.hpp"

namespace aosuite::renderer {

bool osmesa_built() { return false; }

std::unique_ptr<GlContext> detail::make_osmesa_context() {
  throw std::runtime_error("this build has no OSMesa backend");
}

GlProbe detail::probe_osmesa() {
  return {"OSMesa", "osmesa", -1, false, {}, {}, {}, false, "not built"};
}

}  // namespace aosuite::renderer

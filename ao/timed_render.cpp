#include "ao/timed_render.hpp"

#include <vector>

#include "ao/statistics.hpp"

namespace aosuite::ao {

namespace rd = aosuite::renderer;

Timed render_timed(rd::Renderer& renderer, const rd::Scene& scene, const rd::View& view,
                   const rd::RenderSettings& s, int runs) {
  renderer.render(scene, view, s);
  std::vector<double> gl;
  Timed t{{}, 0};
  for (int r = 0; r < runs; ++r) {
    t.images = renderer.render(scene, view, s);
    double g = 0;
    for (const rd::PassTime& p : t.images.times) {
      if (p.pass != "gbuffer" && p.pass != "blend") g += p.gpu_ms;
    }
    gl.push_back(g);
  }
  t.gl_ms = median(gl);
  return t;
}

}  // namespace aosuite::ao

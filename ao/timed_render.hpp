// A frame rendered for its time: one warm-up (llvmpipe compiles shader variants on first use),
// then the median over `runs` frames of the AO work, every pass but the G-buffer and the blend.
#pragma once

#include "renderer/renderer.hpp"

namespace aosuite::ao {

struct Timed {
  renderer::Images images;  // the last run's
  double gl_ms;
};

Timed render_timed(renderer::Renderer& renderer, const renderer::Scene& scene,
                   const renderer::View& view, const renderer::RenderSettings& s, int runs);

}  // namespace aosuite::ao

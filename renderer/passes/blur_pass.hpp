// Pass 3: the separable 21-tap Gaussian over the AO term, optionally depth-aware, as two
// compute dispatches (blur.comp).
#pragma once

#include <array>

#include "renderer/frame.hpp"
#include "renderer/technique.hpp"

namespace aosuite::renderer {

class BlurPass {
 public:
  BlurPass();
  // Blurs `ao` (R32F or wider) in place, using `scratch` (same size, RG32F) between the two
  // axes.
  PassTimer run(const GBuffer& g, Blur blur, GLuint ao, GLuint scratch) const;

 private:
  // [gaussian, bilateral][axis]: the first axis reads AO and the G-buffer's depth and writes
  // (AO, depth) pairs, the second reads the pairs. The kind is compiled in, not a uniform,
  // so the Gaussian does no depth arithmetic.
  std::array<std::array<Program, 2>, 2> axes_;
};

}  // namespace aosuite::renderer

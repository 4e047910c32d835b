// Pass 3: the separable 21-tap Gaussian over the AO term, optionally depth-aware.
#pragma once

#include "renderer/frame.hpp"
#include "renderer/technique.hpp"

namespace aosuite::renderer {

class BlurPass {
 public:
  BlurPass();
  // Blurs `ao` (R32F or wider) in place, using `scratch` (same size, RG32F) between the two
  // axes.
  PassTimer run(const GBuffer& g, Blur blur, GLuint ao, GLuint ao_fb, GLuint scratch,
                GLuint scratch_fb) const;

 private:
  Program first_axis_;   // reads AO and the G-buffer's depth, writes (AO, depth) pairs
  Program second_axis_;  // reads the pairs
};

}  // namespace aosuite::renderer

// Pass 3: the separable 21-tap Gaussian over the AO term, optionally depth-aware.
#pragma once

#include "renderer/frame.hpp"
#include "renderer/technique.hpp"

namespace aosuite::renderer {

class BlurPass {
 public:
  BlurPass();
  // Blurs `ao` in place, using `scratch` (same size, R32F) between the two axes.
  PassTime run(const GBuffer& g, Blur blur, GLuint ao, GLuint ao_fb, GLuint scratch,
               GLuint scratch_fb) const;

 private:
  Program program_;
};

}  // namespace aosuite::renderer

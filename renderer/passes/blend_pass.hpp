// Pass 4: the lit image without AO, with AO multiplied in, and the AO term alone (sRGB).
#pragma once

#include <array>

#include "renderer/frame.hpp"
#include "renderer/technique.hpp"

namespace aosuite::renderer {

// The blend's three RGBA8 images, and a framebuffer drawing to them in that order.
struct BlendTarget {
  GLuint framebuffer = 0;
  std::array<GLuint, 3> images{};  // no AO, with AO, AO only
};

class BlendPass {
 public:
  // blend.frag drawn, or blend.comp dispatched: both blend.glsl.
  explicit BlendPass(Pipeline pipeline);
  // ao == 0 renders without AO (the with-AO image then equals the no-AO one).
  PassTimer run(const GBuffer& g, GLuint ao, const BlendTarget& out) const;

 private:
  Pipeline pipeline_;
  int rows_;  // pixels an invocation of blend.comp shades (light_pass_rows)
  Program program_;
};

}  // namespace aosuite::renderer

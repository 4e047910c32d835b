// Pass 4: the lit image without AO, with AO multiplied in, and the AO term alone (sRGB).
#pragma once

#include "renderer/frame.hpp"

namespace aosuite::renderer {

class BlendPass {
 public:
  BlendPass();
  // ao == 0 renders without AO (the with-AO image then equals the no-AO one).
  PassTimer run(const GBuffer& g, GLuint ao, GLuint out_fb) const;

 private:
  Program program_;
};

}  // namespace aosuite::renderer

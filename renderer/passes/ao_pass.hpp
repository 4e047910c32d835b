// Pass 2: the AO term, one implementation per technique, each writing visibility in [0, 1]
// (1 = unoccluded) to an R32F target at full resolution.
#pragma once

#include <memory>
#include <vector>

#include "renderer/frame.hpp"
#include "renderer/technique.hpp"

namespace aosuite::renderer {

class AoPass {
 public:
  virtual ~AoPass() = default;
  // Returns the timer of each sub-pass (e.g. SAO's pyramid, MSSAO's levels).
  virtual std::vector<PassTimer> run(const GBuffer& g, const Camera& camera, const AoParams& params,
                                     GLuint out_fb) = 0;
};

std::unique_ptr<AoPass> make_ao_pass(Technique technique);

// A technique that is one full-screen draw over the G-buffer's depth and normals with
// `fragment` (a file in renderer/passes/shaders/), which reads shaders/ao_uniforms.glsl's block.
std::unique_ptr<AoPass> make_gbuffer_ao_pass(const char* fragment);

}  // namespace aosuite::renderer

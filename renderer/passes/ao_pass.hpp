// Pass 2: the AO term, one implementation per technique and pipeline, each writing visibility
// in [0, 1] (1 = unoccluded) to an R32F target at full resolution.
#pragma once

#include <memory>
#include <vector>

#include "renderer/frame.hpp"
#include "renderer/technique.hpp"

namespace aosuite::renderer {

// The AO texture, and a framebuffer drawing to it that carries the G-buffer's depth buffer
// (draw_geometry_pixels). Fragment passes draw into the framebuffer, compute passes store
// into the texture.
struct AoTarget {
  GLuint framebuffer = 0, texture = 0;
};

class AoPass {
 public:
  virtual ~AoPass() = default;
  // Returns the timer of each sub-pass (e.g. SAO's pyramid, MSSAO's levels).
  virtual std::vector<PassTimer> run(const GBuffer& g, const Camera& camera, const AoParams& params,
                                     const AoTarget& out) = 0;
};

std::unique_ptr<AoPass> make_ao_pass(Technique technique, Pipeline pipeline);

// The program of an estimator in `pipeline`: "NAME.frag" over the full-screen triangle, or
// "NAME.comp" (both files in renderer/passes/shaders/, including NAME.glsl's estimate_ao).
Program make_ao_program(Pipeline pipeline, const std::string& name);

// Runs `program` (its inputs bound) over every geometry pixel of `out`: a draw_geometry_pixels
// in the fragment pipeline, a dispatch over the whole image in the compute one (whose sky
// pixels estimate_ao answers with 1 before any tap).
void write_ao(Pipeline pipeline, GLuint program, const AoTarget& out, int width, int height);

// A technique that is one pass over the G-buffer's depth and normals with estimator `name`
// (make_ao_program), which reads shaders/ao_uniforms.glsl's block.
std::unique_ptr<AoPass> make_gbuffer_ao_pass(Pipeline pipeline, const std::string& name);

}  // namespace aosuite::renderer

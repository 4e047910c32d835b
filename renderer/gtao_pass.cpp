// GTAO's pass: one full-screen draw of gtao.frag, with its own slice, step and falloff uniforms.
#include "renderer/ao_pass.hpp"

namespace aosuite::renderer {

std::unique_ptr<AoPass> make_gtao_pass() {
  return make_gbuffer_ao_pass("gtao.frag", [](GLuint p, const AoParams& params) {
    glProgramUniform1i(p, glGetUniformLocation(p, "u_slices"), params.gtao.slices);
    glProgramUniform1i(p, glGetUniformLocation(p, "u_steps"), params.gtao.steps);
    glProgramUniform1f(p, glGetUniformLocation(p, "u_falloff_range"), params.gtao.falloff_range);
    glProgramUniform1f(p, glGetUniformLocation(p, "u_thin_occluder"), params.gtao.thin_occluder);
  });
}

}  // namespace aosuite::renderer

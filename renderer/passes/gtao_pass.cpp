// GTAO's pass: one full-screen draw of gtao.frag or one dispatch of gtao.comp (both gtao.glsl);
// its slices, steps and falloff reach the shader through the AO uniform block (ao_uniforms.hpp).
#include "renderer/passes/ao_pass.hpp"

namespace aosuite::renderer {

std::unique_ptr<AoPass> make_gtao_pass() {
  return make_gbuffer_ao_pass(Pipeline::kFragment, "gtao");
}
std::unique_ptr<AoPass> make_gtao_compute_pass() {
  return make_gbuffer_ao_pass(Pipeline::kCompute, "gtao");
}

}  // namespace aosuite::renderer

// GTAO's pass: one full-screen draw of gtao.frag; its slices, steps and falloff reach the
// shader through the AO uniform block (ao_uniforms.hpp).
#include "renderer/passes/ao_pass.hpp"

namespace aosuite::renderer {

std::unique_ptr<AoPass> make_gtao_pass() { return make_gbuffer_ao_pass("gtao.frag"); }

}  // namespace aosuite::renderer

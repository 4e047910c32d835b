// The visibility-bitmask pass: one full-screen draw of bitmask.frag or one dispatch of
// bitmask.comp (both bitmask.glsl), which shares GTAO's slices, steps and noise; its thickness
// reaches the shader through the AO uniform block.
#include "renderer/passes/ao_pass.hpp"

namespace aosuite::renderer {

std::unique_ptr<AoPass> make_bitmask_pass() {
  return make_gbuffer_ao_pass(Pipeline::kFragment, "bitmask");
}
std::unique_ptr<AoPass> make_bitmask_compute_pass() {
  return make_gbuffer_ao_pass(Pipeline::kCompute, "bitmask");
}

}  // namespace aosuite::renderer

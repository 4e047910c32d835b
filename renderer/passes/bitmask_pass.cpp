// The visibility-bitmask pass: one full-screen draw of bitmask.frag, which shares GTAO's
// slices, steps and noise; its thickness reaches the shader through the AO uniform block.
#include "renderer/passes/ao_pass.hpp"

namespace aosuite::renderer {

std::unique_ptr<AoPass> make_bitmask_pass() { return make_gbuffer_ao_pass("bitmask.frag"); }

}  // namespace aosuite::renderer

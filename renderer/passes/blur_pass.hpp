// Pass 3: the separable 21-tap Gaussian over the AO term, optionally depth-aware, as two
// compute dispatches in one of two kernels with the same output to the bit.
#pragma once

#include <array>
#include <cstddef>

#include "renderer/frame.hpp"
#include "renderer/technique.hpp"

namespace aosuite::renderer {

enum class BlurKernel {
  kRuns,   // blur.comp: runs of eight pixels per invocation, for a CPU rasteriser (llvmpipe)
  kTiles,  // blur_tile.comp: a pixel per invocation through shared memory, for GPUs
};

class BlurPass {
 public:
  explicit BlurPass(BlurKernel kernel);
  // Blurs `ao` (R32F, the G-buffer's size) in place.
  PassTimer run(const GBuffer& g, Blur blur, GLuint ao);

 private:
  // [gaussian, bilateral][axis]: the first axis reads AO and the G-buffer's depth and writes
  // (AO, depth) pairs, the second reads the pairs. The kind is compiled in, not a uniform,
  // so the Gaussian does no depth arithmetic.
  bool tiles_;  // blur_tile.comp, which stores into the AO texture, not into blurred_
  std::array<std::array<Program, 2>, 2> axes_;
  // Buffers, not textures, between the axes: on llvmpipe a buffer load or store costs a
  // fraction of a texelFetch or imageStore.
  Buffer pairs_, blurred_;
  std::size_t pixels_ = 0;
};

}  // namespace aosuite::renderer

// The C++ twin of shaders/ao_uniforms.glsl's std140 block: one settings -> constants function
// (ao_uniform_block) and one buffer per pass that holds them, instead of one glProgramUniform
// call per name on programs that may not declare it.
#pragma once

#include <cstddef>
#include <cstdint>

#include "renderer/frame.hpp"
#include "renderer/technique.hpp"

namespace aosuite::renderer {

// std140 packs these scalars at 4-byte steps in declaration order.
struct AoUniformBlock {
  std::int32_t samples;
  float radius, bias, intensity, contrast, turns, max_pixel_radius, proj_scale;
  std::int32_t slices, steps;
  float falloff_range, thin_occluder;
  float thickness;
  std::int32_t exact_plane;
  float std140_padding[2];  // the block's size rounds up to 16 bytes
};
static_assert(offsetof(AoUniformBlock, samples) == 0);
static_assert(offsetof(AoUniformBlock, radius) == 4);
static_assert(offsetof(AoUniformBlock, proj_scale) == 28);
static_assert(offsetof(AoUniformBlock, slices) == 32);
static_assert(offsetof(AoUniformBlock, thin_occluder) == 44);
static_assert(offsetof(AoUniformBlock, thickness) == 48);
static_assert(offsetof(AoUniformBlock, exact_plane) == 52);
static_assert(sizeof(AoUniformBlock) == 64);

inline constexpr GLuint kAoUniformBinding = 0;  // the block's `binding` in the GLSL

// SAO's discrepancy-minimising spiral turns for s samples (G3D's table), 7 beyond it.
int spiral_turns(int samples);

// Every field from the parameters and the camera; max_pixel_radius unbounded (MSSAO caps it).
AoUniformBlock ao_uniform_block(const AoParams& params, const Camera& camera);

// The block's buffer, bound at kAoUniformBinding when uploaded. Uploading between draws is
// ordered by GL like any other command, so a pass may change it per draw (MSSAO's levels).
class AoUniformBuffer {
 public:
  AoUniformBuffer();
  void upload(const AoUniformBlock& block) const;

 private:
  Buffer buffer_;
};

}  // namespace aosuite::renderer

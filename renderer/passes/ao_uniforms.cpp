#include "renderer/passes/ao_uniforms.hpp"

#include <array>

namespace aosuite::renderer {

int spiral_turns(int samples) {
  static constexpr std::array<int, 50> kTurns = {
      1, 1, 1, 2, 3, 2,  5,  2, 3,  2,  3, 3,  5, 5, 3,  4,  7,  5,  5,  7,  9,  8,  5,  5,  7,
      7, 7, 8, 5, 8, 11, 12, 7, 10, 13, 8, 11, 8, 7, 14, 11, 11, 13, 12, 13, 19, 17, 13, 11, 18};
  return samples >= 0 && samples < 50 ? kTurns[static_cast<std::size_t>(samples)] : 7;
}

AoUniformBlock ao_uniform_block(const AoParams& p, const Camera& camera) {
  return {p.samples,
          p.radius * p.radius_scale,
          p.bias,
          p.intensity,
          p.contrast,
          static_cast<float>(spiral_turns(p.samples)),
          1e30f,
          camera.proj_scale,
          p.gtao.slices,
          p.gtao.steps,
          p.gtao.falloff_range,
          p.gtao.thin_occluder,
          p.bitmask.thickness,
          p.gtao.exact_plane,
          {0, 0}};
}

AoUniformBuffer::AoUniformBuffer() : buffer_(make_buffer(nullptr, sizeof(AoUniformBlock))) {}

void AoUniformBuffer::upload(const AoUniformBlock& block) const {
  glNamedBufferSubData(buffer_.get(), 0, sizeof block, &block);
  glBindBufferBase(GL_UNIFORM_BUFFER, kAoUniformBinding, buffer_.get());
}

}  // namespace aosuite::renderer

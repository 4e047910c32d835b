#include "renderer/passes/ao_uniforms.hpp"

#include "renderer/passes/ao_pass.hpp"

namespace aosuite::renderer {

AoUniformBlock ao_uniform_block(const AoParams& p, const Camera& camera) {
  return {p.samples,
          p.radius,
          p.bias,
          p.intensity,
          p.contrast,
          static_cast<float>(spiral_turns(p.samples)),
          1e30f,
          camera.proj_scale,
          p.gtao.slices,
          p.gtao.steps,
          p.gtao.falloff_range,
          p.gtao.thin_occluder};
}

AoUniformBuffer::AoUniformBuffer() : buffer_(make_buffer(nullptr, sizeof(AoUniformBlock))) {}

void AoUniformBuffer::upload(const AoUniformBlock& block) const {
  glNamedBufferSubData(buffer_.get(), 0, sizeof block, &block);
  glBindBufferBase(GL_UNIFORM_BUFFER, kAoUniformBinding, buffer_.get());
}

}  // namespace aosuite::renderer

// Scalable AO (McGuire, Mara, Luebke 2012): a linear-depth pyramid, then the AO pass, which
// uses depth only (no G-buffer normals). The pyramid is a compute pass in both pipelines.
#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "renderer/passes/ao_pass.hpp"
#include "renderer/passes/ao_uniforms.hpp"

namespace aosuite::renderer {
namespace {

constexpr int kLevels = 6;  // level 0 and MAX_MIP_LEVEL = 5 minified levels (sao_pyramid.glsl)
constexpr int kGroup = 8;   // sao_pyramid.comp's workgroup side

GLuint groups(int n) { return static_cast<GLuint>((n + kGroup - 1) / kGroup); }

class SaoPass final : public AoPass {
 public:
  explicit SaoPass(Pipeline pipeline)
      : pipeline_(pipeline),
        pyramid_(make_program({"sao_pyramid.comp"})),
        ao_(make_ao_program(pipeline, "sao")) {}

  std::vector<PassTimer> run(const GBuffer& g, const Camera& camera, const AoParams& params,
                             const AoTarget& out) override {
    if (g.width != width_ || g.height != height_) allocate(g.width, g.height);
    PassTimer pyramid_timer("sao_pyramid");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, pyramid_buffer_.get());
    set_level_uniforms(pyramid_.get());
    bind_textures(pyramid_.get(), {{"u_depth", g.depth.get()}});
    glDispatchCompute(groups(width_), groups(height_), 1);  // every level at once
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    pyramid_timer.stop();

    PassTimer ao_timer("ao");
    const GLuint p = ao_.get();
    set_camera_uniforms(p, camera);
    uniforms_.upload(ao_uniform_block(params, camera));
    set_level_uniforms(p);
    write_ao(pipeline_, p, out, g.width, g.height);
    ao_timer.stop();
    std::vector<PassTimer> times;
    times.push_back(std::move(pyramid_timer));
    times.push_back(std::move(ao_timer));
    return times;
  }

 private:
  // sao_pyramid.glsl's level_size.
  std::array<int, 2> size(int level) const {
    return {std::max(1, width_ >> level), std::max(1, height_ >> level)};
  }
  GLsizei level_bytes(int level) const {
    return static_cast<GLsizei>(sizeof(float)) * size(level)[0] * size(level)[1];
  }

  void allocate(int width, int height) {
    width_ = width, height_ = height;
    levels_ = 1;  // a tiny image has fewer levels than MAX_MIP_LEVEL asks for
    while (levels_ < kLevels && (std::max(width, height) >> levels_) > 0) ++levels_;
    GLsizei bytes = 0;
    for (int level = 0; level < levels_; ++level) {
      offsets_[static_cast<std::size_t>(level)] = bytes / static_cast<GLsizei>(sizeof(float));
      bytes += level_bytes(level);
    }
    pyramid_buffer_ = make_buffer(nullptr, static_cast<std::size_t>(bytes));
  }

  void set_level_uniforms(GLuint program) const {
    glProgramUniform1i(program, glGetUniformLocation(program, "u_levels"), levels_);
    glProgramUniform2i(program, glGetUniformLocation(program, "u_size"), width_, height_);
    for (int level = 0; level < levels_; ++level) {
      glProgramUniform1i(
          program, glGetUniformLocation(program, fmt::format("u_level_offset[{}]", level).c_str()),
          offsets_[static_cast<std::size_t>(level)]);
    }
  }

  Pipeline pipeline_;
  Program pyramid_, ao_;
  AoUniformBuffer uniforms_;
  Buffer pyramid_buffer_;  // sao_pyramid.glsl's layout
  std::array<GLint, kLevels> offsets_{};
  int width_ = 0, height_ = 0, levels_ = 1;
};

}  // namespace

std::unique_ptr<AoPass> make_sao_pass() { return std::make_unique<SaoPass>(Pipeline::kFragment); }
std::unique_ptr<AoPass> make_sao_compute_pass() {
  return std::make_unique<SaoPass>(Pipeline::kCompute);
}

}  // namespace aosuite::renderer

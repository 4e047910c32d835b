#include "renderer/passes/blur_pass.hpp"

#include <string>

namespace aosuite::renderer {

namespace {
constexpr float kEdgeSharpness = 20;  // a tap 5 % deeper or shallower than the centre gets 0
constexpr int kRun = 8;               // pixels per invocation along the axis (blur.comp)
constexpr int kGroup = 8;             // blur.comp's invocations per workgroup side
// blur_tile.comp's tiles (its local sizes), per axis: a row segment, then eight columns.
constexpr int kTile[2][2] = {{64, 1}, {8, 32}};

Program axis_program(BlurKernel kernel, bool bilateral, bool second_axis) {
  const std::string defines = std::string(bilateral ? "#define BILATERAL\n" : "") +
                              (second_axis ? "#define SECOND_AXIS\n" : "");
  if (kernel == BlurKernel::kTiles) {
    return make_program({"blur_tile.comp"}, defines + "#define STORE_TEXTURE\n");
  }
  return make_program({"blur.comp"}, defines + "#define RUN " + std::to_string(kRun) +
                                         "\n#define GROUP " + std::to_string(kGroup) + "\n");
}

GLuint groups(int n, int size) { return static_cast<GLuint>((n + size - 1) / size); }
}  // namespace

BlurPass::BlurPass(BlurKernel kernel)
    : tiles_(kernel == BlurKernel::kTiles),
      axes_{{{{axis_program(kernel, false, false), axis_program(kernel, false, true)}},
             {{axis_program(kernel, true, false), axis_program(kernel, true, true)}}}} {}

PassTimer BlurPass::run(const GBuffer& g, Blur blur, GLuint ao) {
  const auto pixels = static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height);
  if (pixels != pixels_) {
    pixels_ = pixels;
    pairs_ = make_buffer(nullptr, pixels * 2 * sizeof(float));
    if (!tiles_) blurred_ = make_buffer(nullptr, pixels * sizeof(float));
  }
  PassTimer timer("blur");
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, pairs_.get());
  if (!tiles_) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, blurred_.get());
  const auto& axes = axes_[blur == Blur::kBilateral ? 1 : 0];
  for (int axis = 0; axis < 2; ++axis) {
    const GLuint p = axes[static_cast<std::size_t>(axis)].get();
    glProgramUniform1f(p, glGetUniformLocation(p, "u_sharpness"), kEdgeSharpness);
    glProgramUniform2i(p, glGetUniformLocation(p, "u_axis"), axis == 0, axis == 1);
    glProgramUniform2i(p, glGetUniformLocation(p, "u_size"), g.width, g.height);
    if (axis == 0) {
      bind_textures(p, {{"u_ao", ao}, {"u_depth", g.depth.get()}});
    } else {
      glUseProgram(p);
      if (tiles_) glBindImageTexture(0, ao, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    }
    if (tiles_) {
      const int* tile = kTile[axis];
      glDispatchCompute(groups(g.width, tile[0]), groups(g.height, tile[1]), 1);
    } else {
      const int runs_x = axis == 0 ? (g.width + kRun - 1) / kRun : g.width;
      const int runs_y = axis == 0 ? g.height : (g.height + kRun - 1) / kRun;
      glDispatchCompute(groups(runs_x, kGroup), groups(runs_y, kGroup), 1);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                    GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  }
  if (!tiles_) {
    // Back into the AO texture, which the blend and the read-back read: a copy by the driver.
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, blurred_.get());
    glTextureSubImage2D(ao, 0, 0, 0, g.width, g.height, GL_RED, GL_FLOAT, nullptr);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  }
  timer.stop();
  return timer;
}

}  // namespace aosuite::renderer

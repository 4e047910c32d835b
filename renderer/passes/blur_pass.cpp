#include "renderer/passes/blur_pass.hpp"

#include <string>

namespace aosuite::renderer {

namespace {
constexpr float kEdgeSharpness = 20;  // a tap 5 % deeper or shallower than the centre gets 0
constexpr int kRun = 8;               // pixels per invocation along the axis (blur.comp)
constexpr int kGroup = 8;             // invocations per workgroup side

Program axis_program(bool bilateral, bool second_axis) {
  return make_program({"blur.comp"}, "#define RUN " + std::to_string(kRun) + "\n#define GROUP " +
                                         std::to_string(kGroup) + "\n" +
                                         (bilateral ? "#define BILATERAL\n" : "") +
                                         (second_axis ? "#define SECOND_AXIS\n" : ""));
}

GLuint groups(int invocations) { return static_cast<GLuint>((invocations + kGroup - 1) / kGroup); }
}  // namespace

BlurPass::BlurPass()
    : axes_{{{{axis_program(false, false), axis_program(false, true)}},
             {{axis_program(true, false), axis_program(true, true)}}}} {}

PassTimer BlurPass::run(const GBuffer& g, Blur blur, GLuint ao) {
  const auto pixels = static_cast<std::size_t>(g.width) * static_cast<std::size_t>(g.height);
  if (pixels != pixels_) {
    pixels_ = pixels;
    pairs_ = make_buffer(nullptr, pixels * 2 * sizeof(float));
    blurred_ = make_buffer(nullptr, pixels * sizeof(float));
  }
  PassTimer timer("blur");
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, pairs_.get());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, blurred_.get());
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
    }
    const int runs_x = axis == 0 ? (g.width + kRun - 1) / kRun : g.width;
    const int runs_y = axis == 0 ? g.height : (g.height + kRun - 1) / kRun;
    glDispatchCompute(groups(runs_x), groups(runs_y), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
  }
  // Back into the AO texture, which the blend and the read-back read: a copy by the driver.
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, blurred_.get());
  glTextureSubImage2D(ao, 0, 0, 0, g.width, g.height, GL_RED, GL_FLOAT, nullptr);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  timer.stop();
  return timer;
}

}  // namespace aosuite::renderer

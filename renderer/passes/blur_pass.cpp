#include "renderer/passes/blur_pass.hpp"

#include <string>

namespace aosuite::renderer {

namespace {
constexpr float kEdgeSharpness = 20;  // a tap 5 % deeper or shallower than the centre gets 0
constexpr int kRun = 8;               // pixels per invocation along the axis (blur.comp)
constexpr int kGroup = 8;             // invocations per workgroup side

Program axis_program(bool bilateral, bool packed_input) {
  return make_program({"blur.comp"}, "#define RUN " + std::to_string(kRun) + "\n#define GROUP " +
                                         std::to_string(kGroup) + "\n" +
                                         (bilateral ? "#define BILATERAL\n" : "") +
                                         (packed_input ? "#define PACKED_INPUT\n" : ""));
}

GLuint groups(int invocations) { return static_cast<GLuint>((invocations + kGroup - 1) / kGroup); }
}  // namespace

BlurPass::BlurPass()
    : axes_{{{{axis_program(false, false), axis_program(false, true)}},
             {{axis_program(true, false), axis_program(true, true)}}}} {}

PassTimer BlurPass::run(const GBuffer& g, Blur blur, GLuint ao, GLuint scratch) const {
  PassTimer timer("blur");
  const auto& axes = axes_[blur == Blur::kBilateral ? 1 : 0];
  for (const Program& program : axes) {
    const GLuint p = program.get();
    const bool first = &program == &axes[0];
    glProgramUniform1f(p, glGetUniformLocation(p, "u_sharpness"), kEdgeSharpness);
    glProgramUniform2i(p, glGetUniformLocation(p, "u_axis"), first ? 1 : 0, first ? 0 : 1);
    if (first) {
      bind_textures(p, {{"u_ao", ao}, {"u_depth", g.depth.get()}});
    } else {
      bind_textures(p, {{"u_ao", scratch}});
    }
    glBindImageTexture(0, first ? scratch : ao, 0, GL_FALSE, 0, GL_WRITE_ONLY,
                       first ? GL_RG32F : GL_R32F);
    glProgramUniform1i(p, glGetUniformLocation(p, "u_out"), 0);
    const int runs_x = first ? (g.width + kRun - 1) / kRun : g.width;
    const int runs_y = first ? g.height : (g.height + kRun - 1) / kRun;
    glDispatchCompute(groups(runs_x), groups(runs_y), 1);
    // The next axis, the blend and the read-back all read what imageStore wrote.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_FRAMEBUFFER_BARRIER_BIT);
  }
  timer.stop();
  return timer;
}

}  // namespace aosuite::renderer

#include "renderer/passes/blur_pass.hpp"

namespace aosuite::renderer {

namespace {
constexpr float kEdgeSharpness = 20;  // a tap 5 % deeper or shallower than the centre gets 0
}

BlurPass::BlurPass()
    : first_axis_(make_program({"fullscreen.vert", "blur.frag"})),
      second_axis_(make_program({"fullscreen.vert", "blur.frag"}, "#define PACKED_INPUT\n")) {}

PassTimer BlurPass::run(const GBuffer& g, Blur blur, GLuint ao, GLuint ao_fb, GLuint scratch,
                        GLuint scratch_fb) const {
  PassTimer timer("blur");
  for (const Program* program : {&first_axis_, &second_axis_}) {
    const GLuint p = program->get();
    const bool first = program == &first_axis_;
    glProgramUniform1i(p, glGetUniformLocation(p, "u_bilateral"), blur == Blur::kBilateral);
    glProgramUniform1f(p, glGetUniformLocation(p, "u_sharpness"), kEdgeSharpness);
    glProgramUniform2i(p, glGetUniformLocation(p, "u_axis"), first ? 1 : 0, first ? 0 : 1);
    if (first) {
      bind_textures(p, {{"u_ao", ao}, {"u_depth", g.depth.get()}});
    } else {
      bind_textures(p, {{"u_ao", scratch}});
    }
    draw_geometry_pixels(first ? scratch_fb : ao_fb, g.width, g.height);
  }
  timer.stop();
  return timer;
}

}  // namespace aosuite::renderer

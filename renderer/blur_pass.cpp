#include "renderer/blur_pass.hpp"

namespace aosuite::renderer {

namespace {
constexpr float kEdgeSharpness = 20;  // a tap 5 % deeper or shallower than the centre gets 0
}

BlurPass::BlurPass() : program_(make_program({"fullscreen.vert", "blur.frag"})) {}

PassTime BlurPass::run(const GBuffer& g, Blur blur, GLuint ao, GLuint ao_fb, GLuint scratch,
                       GLuint scratch_fb) const {
  PassTimer timer("blur");
  const GLuint p = program_.get();
  glProgramUniform1i(p, glGetUniformLocation(p, "u_bilateral"), blur == Blur::kBilateral);
  glProgramUniform1f(p, glGetUniformLocation(p, "u_sharpness"), kEdgeSharpness);
  glProgramUniform2i(p, glGetUniformLocation(p, "u_axis"), 1, 0);
  bind_textures(p, {{"u_ao", ao}, {"u_depth", g.depth.get()}});
  draw_geometry_pixels(scratch_fb, g.width, g.height);
  glProgramUniform2i(p, glGetUniformLocation(p, "u_axis"), 0, 1);
  bind_textures(p, {{"u_ao", scratch}, {"u_depth", g.depth.get()}});
  draw_geometry_pixels(ao_fb, g.width, g.height);
  return timer.finish();
}

}  // namespace aosuite::renderer

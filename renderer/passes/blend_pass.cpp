#include "renderer/passes/blend_pass.hpp"

namespace aosuite::renderer {

BlendPass::BlendPass() : program_(make_program({"fullscreen.vert", "blend.frag"})) {}

PassTimer BlendPass::run(const GBuffer& g, GLuint ao, GLuint out_fb) const {
  PassTimer timer("blend");
  const GLuint p = program_.get();
  glProgramUniform1i(p, glGetUniformLocation(p, "u_has_ao"), ao != 0);
  bind_textures(p, {{"u_depth", g.depth.get()},
                    {"u_normal", g.normal.get()},
                    {"u_albedo", g.albedo.get()},
                    {"u_ao", ao ? ao : g.depth.get()}});
  draw_fullscreen(out_fb, g.width, g.height);
  timer.stop();
  return timer;
}

}  // namespace aosuite::renderer

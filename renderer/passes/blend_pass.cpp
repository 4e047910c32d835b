#include "renderer/passes/blend_pass.hpp"

namespace aosuite::renderer {

BlendPass::BlendPass(Pipeline pipeline)
    : pipeline_(pipeline),
      rows_(light_pass_rows()),
      program_(pipeline == Pipeline::kCompute ? make_pixel_program("blend.comp", rows_)
                                              : make_program({"fullscreen.vert", "blend.frag"})) {}

PassTimer BlendPass::run(const GBuffer& g, GLuint ao, const BlendTarget& out) const {
  PassTimer timer("blend");
  const GLuint p = program_.get();
  glProgramUniform1i(p, glGetUniformLocation(p, "u_has_ao"), ao != 0);
  bind_textures(p, {{"u_depth", g.depth.get()},
                    {"u_normal", g.normal.get()},
                    {"u_albedo", g.albedo.get()},
                    {"u_ao", ao ? ao : g.depth.get()}});
  if (pipeline_ == Pipeline::kCompute) {
    dispatch_pixels(
        p, {{out.images[0], GL_RGBA8}, {out.images[1], GL_RGBA8}, {out.images[2], GL_RGBA8}},
        g.width, g.height, rows_);
  } else {
    draw_fullscreen(out.framebuffer, g.width, g.height);
  }
  timer.stop();
  return timer;
}

}  // namespace aosuite::renderer

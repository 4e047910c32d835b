#include "renderer/passes/half_res_pass.hpp"

#include <algorithm>

namespace aosuite::renderer {

HalfResPass::HalfResPass(Pipeline pipeline)
    : pipeline_(pipeline),
      downsample_(make_ao_program(pipeline, "mssao_downsample")),
      upsample_(make_ao_program(pipeline, "half_res_upsample")) {}

PassTimer HalfResPass::downsample(const GBuffer& full) {
  const int w = (full.width + 1) / 2, h = (full.height + 1) / 2;
  if (w != half_.width || h != half_.height) {
    half_.width = w, half_.height = h;
    half_.depth = make_texture(GL_R32F, w, h);
    half_.normal = make_texture(GL_RGBA16F, w, h);
    half_.fb = make_framebuffer({half_.depth.get(), half_.normal.get()});
    ao_ = make_texture(GL_R32F, w, h);
    ao_fb_ = make_framebuffer({ao_.get()});
  }
  PassTimer timer("half_downsample");
  const GLuint d = downsample_.get();
  bind_textures(d, {{"u_depth", full.depth.get()}, {"u_normal", full.normal.get()}});
  if (pipeline_ == Pipeline::kCompute) {
    dispatch_pixels(d, {{half_.depth.get(), GL_R32F}, {half_.normal.get(), GL_RGBA16F}}, w, h);
  } else {
    draw_fullscreen(half_.fb.get(), w, h);
  }
  timer.stop();
  return timer;
}

Camera HalfResPass::camera(const Camera& full) const {
  Camera c = full;
  c.width = half_.width, c.height = half_.height;
  // Pixels per unit at distance 1 scale with the image's height (frame.hpp).
  c.proj_scale = full.proj_scale * static_cast<float>(half_.height) /
                 static_cast<float>(std::max(full.height, 1));
  return c;
}

PassTimer HalfResPass::upsample(const GBuffer& full, const AoTarget& out) {
  PassTimer timer("half_upsample");
  const GLuint u = upsample_.get();
  bind_textures(u, {{"u_depth", full.depth.get()},
                    {"u_normal", full.normal.get()},
                    {"u_half_ao", ao_.get()},
                    {"u_half_depth", half_.depth.get()},
                    {"u_half_normal", half_.normal.get()}});
  write_ao(pipeline_, u, out, full.width, full.height);
  timer.stop();
  return timer;
}

}  // namespace aosuite::renderer

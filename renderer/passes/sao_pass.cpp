// Scalable AO (McGuire, Mara, Luebke 2012): a linear-depth pyramid, then the AO pass, which
// uses depth only (no G-buffer normals).
#include <algorithm>

#include "renderer/passes/ao_pass.hpp"
#include "renderer/passes/ao_uniforms.hpp"

namespace aosuite::renderer {
namespace {

constexpr int kLevels = 6;  // level 0 and MAX_MIP_LEVEL = 5 minified levels

class SaoPass final : public AoPass {
 public:
  SaoPass()
      : minify_(make_program({"fullscreen.vert", "sao_minify.frag"})),
        ao_(make_program({"fullscreen.vert", "sao.frag"})) {}

  std::vector<PassTimer> run(const GBuffer& g, const Camera& camera, const AoParams& params,
                             GLuint out_fb) override {
    if (g.width != width_ || g.height != height_) allocate(g.width, g.height);
    PassTimer pyramid_timer("sao_pyramid");
    glCopyImageSubData(g.depth.get(), GL_TEXTURE_2D, 0, 0, 0, 0, pyramid_.get(), GL_TEXTURE_2D, 0,
                       0, 0, 0, g.width, g.height, 1);
    const GLuint tex = pyramid_.get();
    for (int level = 1; level < levels_; ++level) {
      // Sample level - 1 only, so drawing into `level` of the same texture is no feedback loop.
      glTextureParameteri(tex, GL_TEXTURE_BASE_LEVEL, level - 1);
      glTextureParameteri(tex, GL_TEXTURE_MAX_LEVEL, level - 1);
      bind_textures(minify_.get(), {{"u_depth", tex}});
      draw_fullscreen(level_fbs_[static_cast<std::size_t>(level)].get(),
                      std::max(1, g.width >> level), std::max(1, g.height >> level));
    }
    glTextureParameteri(tex, GL_TEXTURE_BASE_LEVEL, 0);
    glTextureParameteri(tex, GL_TEXTURE_MAX_LEVEL, levels_ - 1);
    pyramid_timer.stop();

    PassTimer ao_timer("ao");
    const GLuint p = ao_.get();
    set_camera_uniforms(p, camera);
    uniforms_.upload(ao_uniform_block(params, camera));
    glProgramUniform1i(p, glGetUniformLocation(p, "u_max_level"), levels_ - 1);
    bind_textures(p, {{"u_depth", tex}});
    draw_geometry_pixels(out_fb, g.width, g.height);
    ao_timer.stop();
    std::vector<PassTimer> times;
    times.push_back(std::move(pyramid_timer));
    times.push_back(std::move(ao_timer));
    return times;
  }

 private:
  void allocate(int width, int height) {
    width_ = width, height_ = height;
    levels_ = 1;  // a tiny image has fewer levels than MAX_MIP_LEVEL asks for
    while (levels_ < kLevels && (std::max(width, height) >> levels_) > 0) ++levels_;
    pyramid_ = make_texture(GL_R32F, width, height, levels_);
    level_fbs_.clear();
    for (int level = 0; level < levels_; ++level) {
      level_fbs_.push_back(make_framebuffer({pyramid_.get()}, 0, level));
    }
  }

  Program minify_, ao_;
  AoUniformBuffer uniforms_;
  Texture pyramid_;
  std::vector<Framebuffer> level_fbs_;
  int width_ = 0, height_ = 0, levels_ = 1;
};

}  // namespace

std::unique_ptr<AoPass> make_sao_pass() { return std::make_unique<SaoPass>(); }

}  // namespace aosuite::renderer

// Multi-Scale AO (Hoang & Low 2012) with Alchemy as the per-level estimator: five
// resolutions, each with its own intensity, combined coarse to fine through a depth- and
// normal-aware upsampling. Levels coarser than the last non-zero weight are not computed;
// a zero-weight level in between is only downsampled and passed through. In the compute
// pipeline each draw is a dispatch of the same code (mssao_downsample.glsl, mssao_level.glsl).
#include <algorithm>
#include <array>

#include "renderer/passes/ao_pass.hpp"
#include "renderer/passes/ao_uniforms.hpp"

namespace aosuite::renderer {
namespace {

constexpr int kLevels = 5;

struct Level {
  int width = 0, height = 0;
  Texture depth, normal, result;  // result: RG = (max occlusion, summed occlusion)
  Framebuffer gbuffer_fb, result_fb;
};

class MssaoPass final : public AoPass {
 public:
  explicit MssaoPass(Pipeline pipeline)
      : pipeline_(pipeline),
        downsample_(make_ao_program(pipeline, "mssao_downsample")),
        level_(make_ao_program(pipeline, "mssao_level")) {}

  std::vector<PassTimer> run(const GBuffer& g, const Camera& camera, const AoParams& params,
                             const AoTarget& out) override {
    int top = -1;  // the coarsest level that contributes
    int contributing = 0;
    for (int l = 0; l < kLevels; ++l) {
      if (params.mssao.level_weights[static_cast<std::size_t>(l)] > 0) top = l, ++contributing;
    }
    std::vector<PassTimer> times;
    if (top < 0) {  // every weight 0: no occlusion at all
      const float one = 1;
      glClearNamedFramebufferfv(out.framebuffer, GL_COLOR, 0, &one);
      return times;
    }
    if (g.width != width_ || g.height != height_) allocate(g.width, g.height);
    auto depth_of = [&](int l) { return l == 0 ? g.depth.get() : levels_[l].depth.get(); };
    auto normal_of = [&](int l) { return l == 0 ? g.normal.get() : levels_[l].normal.get(); };

    PassTimer down_timer("mssao_downsample");
    const GLuint d = downsample_.get();
    for (int l = 1; l <= top; ++l) {
      bind_textures(d, {{"u_depth", depth_of(l - 1)}, {"u_normal", normal_of(l - 1)}});
      const Level& lv = levels_[l];
      if (pipeline_ == Pipeline::kCompute) {
        dispatch_pixels(d, {{lv.depth.get(), GL_R32F}, {lv.normal.get(), GL_RGBA16F}}, lv.width,
                        lv.height);
      } else {
        draw_fullscreen(lv.gbuffer_fb.get(), lv.width, lv.height);
      }
    }
    down_timer.stop();
    times.push_back(std::move(down_timer));

    const GLuint p = level_.get();
    for (int l = top; l >= 0; --l) {
      PassTimer timer("mssao_level" + std::to_string(l));
      AoParams level_params = params;
      // `intensity` scales every level, as it scales the other techniques' AO.
      level_params.intensity =
          params.intensity * params.mssao.level_weights[static_cast<std::size_t>(l)];
      // A coarse texel's position is off by up to its footprint, which grows 2x per level;
      // the depth-proportional bias grows with it, or flat ground self-occludes at level 4.
      level_params.bias = params.bias * static_cast<float>(1 << l);
      Camera level_camera = camera;
      level_camera.proj_scale = camera.proj_scale / static_cast<float>(1 << l);
      set_camera_uniforms(p, level_camera);
      AoUniformBlock block = ao_uniform_block(level_params, level_camera);
      block.max_pixel_radius = params.mssao.max_pixel_radius;
      uniforms_.upload(block);
      glProgramUniform1i(p, glGetUniformLocation(p, "u_has_coarse"), l < top);
      glProgramUniform1i(p, glGetUniformLocation(p, "u_local"), level_params.intensity > 0);
      glProgramUniform1i(p, glGetUniformLocation(p, "u_finest"), l == 0);
      glProgramUniform1f(p, glGetUniformLocation(p, "u_levels"), static_cast<float>(contributing));
      const int c = std::min(l + 1, top);
      bind_textures(p, {{"u_depth", depth_of(l)},
                        {"u_normal", normal_of(l)},
                        {"u_coarse", levels_[c].result.get()},
                        {"u_coarse_depth", depth_of(c)},
                        {"u_coarse_normal", normal_of(c)}});
      const Level& lv = levels_[l];
      if (l == 0) {
        write_ao(pipeline_, p, out, g.width, g.height);
      } else if (pipeline_ == Pipeline::kCompute) {
        dispatch_pixels(p, {{lv.result.get(), GL_RG32F}}, lv.width, lv.height);
      } else {
        draw_fullscreen(lv.result_fb.get(), lv.width, lv.height);
      }
      timer.stop();
      times.push_back(std::move(timer));
    }
    return times;
  }

 private:
  void allocate(int width, int height) {
    width_ = width, height_ = height;
    for (int l = 0; l < kLevels; ++l) {
      Level& lv = levels_[l];
      lv.width = std::max(1, (width + (1 << l) - 1) >> l);
      lv.height = std::max(1, (height + (1 << l) - 1) >> l);
      lv.result = make_texture(GL_RG32F, lv.width, lv.height);
      lv.result_fb = make_framebuffer({lv.result.get()});
      if (l == 0) continue;  // level 0 reads the G-buffer itself
      lv.depth = make_texture(GL_R32F, lv.width, lv.height);
      lv.normal = make_texture(GL_RGBA16F, lv.width, lv.height);
      lv.gbuffer_fb = make_framebuffer({lv.depth.get(), lv.normal.get()});
    }
  }

  Pipeline pipeline_;
  Program downsample_, level_;
  AoUniformBuffer uniforms_;
  std::array<Level, kLevels> levels_;
  int width_ = 0, height_ = 0;
};

}  // namespace

std::unique_ptr<AoPass> make_mssao_pass() {
  return std::make_unique<MssaoPass>(Pipeline::kFragment);
}
std::unique_ptr<AoPass> make_mssao_compute_pass() {
  return std::make_unique<MssaoPass>(Pipeline::kCompute);
}

}  // namespace aosuite::renderer

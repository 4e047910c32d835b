// Alchemy AO (McGuire et al. 2011) over the G-buffer's depth and normals.
#include "renderer/ao_pass.hpp"

namespace aosuite::renderer {
namespace {

class AlchemyPass final : public AoPass {
 public:
  AlchemyPass() : program_(make_program({"fullscreen.vert", "alchemy.frag"})) {}
  std::vector<PassTime> run(const GBuffer& g, const Camera& camera, const AoParams& params,
                            GLuint out_fb) override {
    PassTimer timer("ao");
    const GLuint p = program_.get();
    set_ao_uniforms(p, params, camera);
    bind_textures(p, {{"u_depth", g.depth.get()}, {"u_normal", g.normal.get()}});
    draw_fullscreen(out_fb, g.width, g.height);
    return {timer.finish()};
  }

 private:
  Program program_;
};

}  // namespace

std::unique_ptr<AoPass> make_alchemy_pass() { return std::make_unique<AlchemyPass>(); }

}  // namespace aosuite::renderer

// Unreal Engine 4 AO (Mittring 2012): paired horizon samples clamped by the G-buffer normal.
#include "renderer/ao_pass.hpp"

namespace aosuite::renderer {
namespace {

class Ue4Pass final : public AoPass {
 public:
  Ue4Pass() : program_(make_program({"fullscreen.vert", "ue4.frag"})) {}
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

std::unique_ptr<AoPass> make_ue4_pass() { return std::make_unique<Ue4Pass>(); }

}  // namespace aosuite::renderer

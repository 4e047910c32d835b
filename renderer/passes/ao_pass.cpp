#include "renderer/passes/ao_pass.hpp"

#include <stdexcept>

#include "renderer/passes/ao_uniforms.hpp"

namespace aosuite::renderer {

namespace {

// A technique that is one full-screen draw over the G-buffer's depth and normals (Alchemy,
// UE4, GTAO); each shader's header has the estimator.
class GBufferAoPass final : public AoPass {
 public:
  explicit GBufferAoPass(const char* fragment)
      : program_(make_program({"fullscreen.vert", fragment})) {}
  std::vector<PassTimer> run(const GBuffer& g, const Camera& camera, const AoParams& params,
                             GLuint out_fb) override {
    PassTimer timer("ao");
    const GLuint p = program_.get();
    set_camera_uniforms(p, camera);
    uniforms_.upload(ao_uniform_block(params, camera));
    bind_textures(p, {{"u_depth", g.depth.get()}, {"u_normal", g.normal.get()}});
    draw_geometry_pixels(out_fb, g.width, g.height);
    timer.stop();
    std::vector<PassTimer> times;
    times.push_back(std::move(timer));
    return times;
  }

 private:
  Program program_;
  AoUniformBuffer uniforms_;
};

}  // namespace

std::unique_ptr<AoPass> make_gbuffer_ao_pass(const char* fragment) {
  return std::make_unique<GBufferAoPass>(fragment);
}

std::unique_ptr<AoPass> make_alchemy_pass() { return make_gbuffer_ao_pass("alchemy.frag"); }

std::unique_ptr<AoPass> make_ue4_pass() { return make_gbuffer_ao_pass("ue4.frag"); }

std::unique_ptr<AoPass> make_ao_pass(Technique technique) {
  const TechniqueInfo& info = technique_info(technique);
  if (!info.make_pass) {
    throw std::invalid_argument(std::string(info.name) + " is not a screen-space technique");
  }
  return info.make_pass();
}

}  // namespace aosuite::renderer

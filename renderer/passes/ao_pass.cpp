#include "renderer/passes/ao_pass.hpp"

#include <stdexcept>

#include "renderer/passes/ao_uniforms.hpp"

namespace aosuite::renderer {

namespace {

// A technique that is one pass over the G-buffer's depth and normals (Alchemy, UE4, GTAO,
// bitmask); each shader's .glsl has the estimator.
class GBufferAoPass final : public AoPass {
 public:
  GBufferAoPass(Pipeline pipeline, const std::string& name)
      : pipeline_(pipeline), program_(make_ao_program(pipeline, name)) {}
  std::vector<PassTimer> run(const GBuffer& g, const Camera& camera, const AoParams& params,
                             const AoTarget& out) override {
    PassTimer timer("ao");
    const GLuint p = program_.get();
    set_camera_uniforms(p, camera);
    uniforms_.upload(ao_uniform_block(params, camera));
    bind_textures(p, {{"u_depth", g.depth.get()}, {"u_normal", g.normal.get()}});
    write_ao(pipeline_, p, out, g.width, g.height);
    timer.stop();
    std::vector<PassTimer> times;
    times.push_back(std::move(timer));
    return times;
  }

 private:
  Pipeline pipeline_;
  Program program_;
  AoUniformBuffer uniforms_;
};

}  // namespace

Program make_ao_program(Pipeline pipeline, const std::string& name) {
  if (pipeline == Pipeline::kCompute) return make_pixel_program((name + ".comp").c_str());
  return make_program({"fullscreen.vert", (name + ".frag").c_str()});
}

void write_ao(Pipeline pipeline, GLuint program, const AoTarget& out, int width, int height) {
  if (pipeline == Pipeline::kCompute) {
    dispatch_pixels(program, {{out.texture, GL_R32F}}, width, height);
  } else {
    glUseProgram(program);
    draw_geometry_pixels(out.framebuffer, width, height);
  }
}

std::unique_ptr<AoPass> make_gbuffer_ao_pass(Pipeline pipeline, const std::string& name) {
  return std::make_unique<GBufferAoPass>(pipeline, name);
}

std::unique_ptr<AoPass> make_alchemy_pass() {
  return make_gbuffer_ao_pass(Pipeline::kFragment, "alchemy");
}
std::unique_ptr<AoPass> make_alchemy_compute_pass() {
  return make_gbuffer_ao_pass(Pipeline::kCompute, "alchemy");
}

std::unique_ptr<AoPass> make_ue4_pass() { return make_gbuffer_ao_pass(Pipeline::kFragment, "ue4"); }
std::unique_ptr<AoPass> make_ue4_compute_pass() {
  return make_gbuffer_ao_pass(Pipeline::kCompute, "ue4");
}

std::unique_ptr<AoPass> make_ao_pass(Technique technique, Pipeline pipeline) {
  const TechniqueInfo& info = technique_info(technique);
  const auto make =
      pipeline == Pipeline::kCompute ? info.make_compute_pass : info.make_fragment_pass;
  if (!make) {
    throw std::invalid_argument(std::string(info.name) + " is not a screen-space technique");
  }
  return make();
}

}  // namespace aosuite::renderer

#include "renderer/ao_pass.hpp"

#include <array>

namespace aosuite::renderer {

std::unique_ptr<AoPass> make_alchemy_pass();
std::unique_ptr<AoPass> make_sao_pass();
std::unique_ptr<AoPass> make_ue4_pass();
std::unique_ptr<AoPass> make_mssao_pass();

std::unique_ptr<AoPass> make_ao_pass(Technique technique) {
  switch (technique) {
    case Technique::kAlchemy:
      return make_alchemy_pass();
    case Technique::kSao:
      return make_sao_pass();
    case Technique::kUe4:
      return make_ue4_pass();
    case Technique::kMssao:
      return make_mssao_pass();
  }
  return make_alchemy_pass();
}

int spiral_turns(int samples) {
  static constexpr std::array<int, 50> kTurns = {
      1, 1, 1, 2, 3, 2,  5,  2, 3,  2,  3, 3,  5, 5, 3,  4,  7,  5,  5,  7,  9,  8,  5,  5,  7,
      7, 7, 8, 5, 8, 11, 12, 7, 10, 13, 8, 11, 8, 7, 14, 11, 11, 13, 12, 13, 19, 17, 13, 11, 18};
  return samples >= 0 && samples < 50 ? kTurns[static_cast<std::size_t>(samples)] : 7;
}

void set_ao_uniforms(GLuint p, const AoParams& params, const Camera& camera) {
  set_camera_uniforms(p, camera);
  glProgramUniform1i(p, glGetUniformLocation(p, "u_samples"), params.samples);
  glProgramUniform1f(p, glGetUniformLocation(p, "u_radius"), params.radius);
  glProgramUniform1f(p, glGetUniformLocation(p, "u_bias"), params.bias);
  glProgramUniform1f(p, glGetUniformLocation(p, "u_intensity"), params.intensity);
  glProgramUniform1f(p, glGetUniformLocation(p, "u_contrast"), params.contrast);
  glProgramUniform1f(p, glGetUniformLocation(p, "u_turns"),
                     static_cast<float>(spiral_turns(params.samples)));
  glProgramUniform1f(p, glGetUniformLocation(p, "u_max_pixel_radius"), 1e30f);
}

void bind_textures(GLuint program, std::initializer_list<std::pair<const char*, GLuint>> textures) {
  glUseProgram(program);
  GLint unit = 0;
  for (const auto& [name, tex] : textures) {
    glBindTextureUnit(static_cast<GLuint>(unit), tex);
    glProgramUniform1i(program, glGetUniformLocation(program, name), unit);
    ++unit;
  }
}

}  // namespace aosuite::renderer

#include "renderer/pmi/pmi_pass.hpp"

#include <stdexcept>
#include <vector>

namespace aosuite::renderer {

PmiPass::PmiPass() : program_(make_program({"pmi_ao.vert", "pmi_ao.frag"})) {}

PassTimer PmiPass::run(const Scene& scene, const PmiMaps& maps, const Camera& camera,
                       const AoParams& params, GLuint out_fb) const {
  if (maps.object.mesh_vertex_base.size() != scene.meshes.size() ||
      maps.vertex_visibility.size() != maps.object.positions.size()) {
    throw std::invalid_argument("PMI maps do not belong to scene '" + scene.name + "'");
  }
  PassTimer timer("ao");
  struct Vertex {
    glm::vec3 position;
    float visibility;
  };
  std::vector<Vertex> vertices;
  std::vector<GLuint> indices;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const Mesh& mesh = scene.meshes[m];
    const int object_base = maps.object.mesh_vertex_base.at(m);
    const auto base = static_cast<GLuint>(vertices.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const float v = object_base < 0
                          ? 1.0f
                          : maps.vertex_visibility[static_cast<std::size_t>(object_base) + i];
      vertices.push_back({mesh.positions[i], v});
    }
    for (const glm::uvec3& t : mesh.triangles) {
      const std::size_t n = mesh.positions.size();
      if (t.x < n && t.y < n && t.z < n)
        indices.insert(indices.end(), {base + t.x, base + t.y, base + t.z});
    }
  }
  static_assert(sizeof(Vertex) == 4 * sizeof(float));
  const IndexedMesh mesh({reinterpret_cast<const float*>(vertices.data()), vertices.size() * 4},
                         {3, 1}, indices);

  glBindFramebuffer(GL_FRAMEBUFFER, out_fb);
  glViewport(0, 0, camera.width, camera.height);
  const float sky = 1;
  glClearBufferfv(GL_COLOR, 0, &sky);
  // The G-buffer's own depth, same transform: only its nearest surfaces pass (reversed Z).
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GEQUAL);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  const GLuint p = program_.get();
  glUseProgram(p);
  set_view_projection(p, camera);
  glProgramUniform1f(p, glGetUniformLocation(p, "u_intensity"), params.intensity);
  glProgramUniform1f(p, glGetUniformLocation(p, "u_contrast"), params.contrast);
  mesh.draw();
  check_gl("PMI pass");
  timer.stop();
  return timer;
}

}  // namespace aosuite::renderer

#include "renderer/passes/gbuffer_pass.hpp"

#include <cmath>
#include <vector>

namespace aosuite::renderer {

namespace {

IndexedMesh upload(const Scene& scene) {
  struct Vertex {
    glm::vec3 position, normal, colour;
  };
  std::vector<Vertex> vertices;
  std::vector<GLuint> indices;
  for (const Mesh& m : scene.meshes) {
    const auto base = static_cast<GLuint>(vertices.size());
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      const glm::vec3 n = i < m.normals.size() ? m.normals[i] : glm::vec3(0);
      vertices.push_back({m.positions[i], n, m.colour});
    }
    for (const glm::uvec3& t : m.triangles) {
      // Indices out of range would read garbage: a malformed mesh loses those triangles.
      if (t.x >= m.positions.size() || t.y >= m.positions.size() || t.z >= m.positions.size())
        continue;
      const glm::vec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
      if (!std::isfinite(a.x + a.y + a.z + b.x + b.y + b.z + c.x + c.y + c.z)) continue;
      indices.insert(indices.end(), {base + t.x, base + t.y, base + t.z});
    }
  }
  static_assert(sizeof(Vertex) == 9 * sizeof(float));
  return IndexedMesh({reinterpret_cast<const float*>(vertices.data()), vertices.size() * 9},
                     {3, 3, 3}, indices);
}

}  // namespace

GpuScene::GpuScene(const Scene& scene) : mesh_(upload(scene)) {}

GBufferPass::GBufferPass() : program_(make_program({"gbuffer.vert", "gbuffer.frag"})) {}

void GBufferPass::run(const GpuScene& scene, const Camera& camera, const GBuffer& g) const {
  glBindFramebuffer(GL_FRAMEBUFFER, g.fb.get());
  glViewport(0, 0, g.width, g.height);
  const float zero[4] = {0, 0, 0, 0};
  for (GLint i = 0; i < 3; ++i) glClearBufferfv(GL_COLOR, i, zero);
  glDepthMask(GL_TRUE);       // geometry-only passes turn depth writes off
  const float far_depth = 0;  // reversed Z: 0 is infinitely far
  glClearBufferfv(GL_DEPTH, 0, &far_depth);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDisable(GL_CULL_FACE);  // two-sided: cameras inside geometry still see surfaces
  const GLuint p = program_.get();
  glUseProgram(p);
  set_view_projection(p, camera);
  scene.draw();
  check_gl("G-buffer pass");
}

}  // namespace aosuite::renderer

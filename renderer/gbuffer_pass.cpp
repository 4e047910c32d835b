#include "renderer/gbuffer_pass.hpp"

#include <cmath>
#include <glm/gtc/type_ptr.hpp>
#include <vector>

namespace aosuite::renderer {

GpuScene::GpuScene(const Scene& scene) {
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
  index_count_ = static_cast<GLsizei>(indices.size());
  GLuint ids[2] = {0, 0};
  glCreateBuffers(2, ids);
  vertices_ = Buffer(ids[0]);
  indices_ = Buffer(ids[1]);
  glNamedBufferStorage(
      ids[0], static_cast<GLsizeiptr>(std::max<std::size_t>(1, vertices.size()) * sizeof(Vertex)),
      vertices.empty() ? nullptr : vertices.data(), 0);
  glNamedBufferStorage(
      ids[1], static_cast<GLsizeiptr>(std::max<std::size_t>(1, indices.size()) * sizeof(GLuint)),
      indices.empty() ? nullptr : indices.data(), 0);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  vao_ = VertexArray(vao);
  glVertexArrayVertexBuffer(vao, 0, ids[0], 0, sizeof(Vertex));
  glVertexArrayElementBuffer(vao, ids[1]);
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(vao, a);
    glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, a * sizeof(glm::vec3));
    glVertexArrayAttribBinding(vao, a, 0);
  }
  check_gl("GpuScene upload");
}

void GpuScene::draw() const {
  if (index_count_ == 0) return;
  // Every other pass draws with the context's attribute-less vertex array (GlContext); put
  // it back afterwards.
  GLint previous = 0;
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &previous);
  glBindVertexArray(vao_.get());
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(static_cast<GLuint>(previous));
}

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
  glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "u_view"), 1, GL_FALSE,
                            glm::value_ptr(camera.view));
  glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "u_projection"), 1, GL_FALSE,
                            glm::value_ptr(camera.projection));
  scene.draw();
  check_gl("G-buffer pass");
}

}  // namespace aosuite::renderer

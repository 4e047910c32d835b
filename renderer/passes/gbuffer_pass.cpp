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

namespace {
// Clears the reversed-Z depth buffer to 0 (infinitely far) and sets the depth test for it.
void begin_scene_depth(GLuint framebuffer, const GBuffer& g) {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glViewport(0, 0, g.width, g.height);
  glDepthMask(GL_TRUE);       // geometry-only passes turn depth writes off
  const float far_depth = 0;  // reversed Z: 0 is infinitely far
  glClearBufferfv(GL_DEPTH, 0, &far_depth);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glDisable(GL_CULL_FACE);  // two-sided: cameras inside geometry still see surfaces
}
}  // namespace

void GBufferPass::run(const GpuScene& scene, const Camera& camera, const GBuffer& g) const {
  begin_scene_depth(g.fb.get(), g);
  const float zero[4] = {0, 0, 0, 0};
  for (GLint i = 0; i < 3; ++i) glClearBufferfv(GL_COLOR, i, zero);
  const GLuint p = program_.get();
  glUseProgram(p);
  set_view_projection(p, camera);
  scene.draw();
  check_gl("G-buffer pass");
}

DepthGBufferPass::DepthGBufferPass()
    : raster_(make_program({"gbuffer.vert"})),
      rows_(light_pass_rows()),
      reconstruct_(make_pixel_program("depth_gbuffer.comp", rows_)) {}

std::vector<PassTimer> DepthGBufferPass::run(const GpuScene& scene, const Camera& camera,
                                             const GBuffer& g) {
  if (framebuffer_zbuffer_ != g.zbuffer.get()) {
    depth_only_ = make_framebuffer({}, g.zbuffer.get());
    framebuffer_zbuffer_ = g.zbuffer.get();
  }
  std::vector<PassTimer> times;
  times.emplace_back("gbuffer");
  begin_scene_depth(depth_only_.get(), g);
  glUseProgram(raster_.get());
  set_view_projection(raster_.get(), camera);
  scene.draw();
  times.back().stop();
  times.emplace_back("gbuffer_normals");
  const GLuint p = reconstruct_.get();
  set_camera_uniforms(p, camera);
  glProgramUniform1f(p, glGetUniformLocation(p, "u_near"), camera.projection[3][2]);
  bind_textures(p, {{"u_zbuffer", g.zbuffer.get()}});
  dispatch_pixels(p, {{g.depth.get(), GL_R32F}, {g.normal.get(), GL_RGBA16F}}, g.width, g.height,
                  rows_);
  times.back().stop();
  check_gl("depth-only G-buffer pass");
  return times;
}

}  // namespace aosuite::renderer

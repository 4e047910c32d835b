#include "renderer/pmi/pmi_item_buffer.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace aosuite::renderer {
namespace {

constexpr GLuint kGroup = 16;  // pmi_histogram.comp's local size per axis

// A perspective camera at `eye` with its clip planes just around the bounding sphere (depth
// precision).
glm::mat4 view_projection(const PmiObject& object, glm::vec3 eye, float aspect) {
  const View v = viewpoint_view(object, eye);
  return glm::perspectiveRH_ZO(glm::radians(v.fovy_degrees), aspect, v.near,
                               viewpoint_far(object, eye)) *
         glm::lookAt(v.eye, v.target, v.up);
}

}  // namespace

ItemBuffer::ItemBuffer(const PmiObject& object, int width, int height)
    : object_(object),
      width_(width),
      height_(height),
      draw_(make_program({"pmi_id.vert", "pmi_id.frag"})),
      histogram_(make_program({"pmi_histogram.comp"})),
      mesh_({glm::value_ptr(object.positions.front()), object.positions.size() * 3}, {3},
            {glm::value_ptr(object.triangles.front()), object.triangles.size() * 3}),
      counters_(make_buffer(nullptr, object.triangles.size() * sizeof(std::uint32_t))),
      ids_(make_texture(GL_R32UI, width, height)),
      depth_(make_texture(GL_DEPTH_COMPONENT32F, width, height)),
      fb_(make_framebuffer({ids_.get()}, depth_.get())),
      counts_(object.triangles.size()) {
  check_gl("item buffer setup");
}

const std::vector<std::uint32_t>& ItemBuffer::count(glm::vec3 eye) {
  // Draw: ID = gl_PrimitiveID + 1 (0 = background), nearest polygon wins, no blending.
  glBindFramebuffer(GL_FRAMEBUFFER, fb_.get());
  glViewport(0, 0, width_, height_);
  const GLuint background = 0;
  glClearBufferuiv(GL_COLOR, 0, &background);
  glDepthMask(GL_TRUE);
  const float far_depth = 1;
  glClearBufferfv(GL_DEPTH, 0, &far_depth);
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);  // the paper projects polygons, whichever side faces the view
  glDisable(GL_BLEND);
  const GLuint d = draw_.get();
  glUseProgram(d);
  const glm::mat4 mvp =
      view_projection(object_, eye, static_cast<float>(width_) / static_cast<float>(height_));
  glProgramUniformMatrix4fv(d, glGetUniformLocation(d, "u_view_projection"), 1, GL_FALSE,
                            glm::value_ptr(mvp));
  mesh_.draw();

  // Histogram: one atomic add per object pixel into the zeroed counters.
  glClearNamedBufferData(counters_.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &background);
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
  glUseProgram(histogram_.get());
  glBindImageTexture(0, ids_.get(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, counters_.get());
  glDispatchCompute((static_cast<GLuint>(width_) + kGroup - 1) / kGroup,
                    (static_cast<GLuint>(height_) + kGroup - 1) / kGroup, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(counters_.get(), 0,
                          static_cast<GLsizeiptr>(counts_.size() * sizeof(std::uint32_t)),
                          counts_.data());
  check_gl("item buffer count");
  return counts_;
}

}  // namespace aosuite::renderer

// Small RAII owners for GL objects, and the helpers every pass uses.
#pragma once

#include <initializer_list>
#include <span>
#include <string>
#include <utility>

#include "renderer/gl/gl.hpp"

namespace aosuite::renderer {

// A GL name with its deleter; movable, not copyable.
template <void (*Delete)(GLuint)>
class GlName {
 public:
  GlName() = default;
  explicit GlName(GLuint id) : id_(id) {}
  GlName(GlName&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
  GlName& operator=(GlName&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0);
    }
    return *this;
  }
  ~GlName() { reset(); }
  GLuint get() const { return id_; }

 private:
  void reset() {
    if (id_) Delete(id_);
    id_ = 0;
  }
  GLuint id_ = 0;
};

void delete_texture(GLuint id);
void delete_framebuffer(GLuint id);
void delete_program(GLuint id);
void delete_buffer(GLuint id);
void delete_vertex_array(GLuint id);
void delete_query(GLuint id);

using Texture = GlName<delete_texture>;
using Framebuffer = GlName<delete_framebuffer>;
using Program = GlName<delete_program>;
using Buffer = GlName<delete_buffer>;
using VertexArray = GlName<delete_vertex_array>;
using Query = GlName<delete_query>;

// A buffer of `bytes` (at least 4) holding `data`; with no data it is writable by
// glNamedBufferSubData/glClearNamedBufferData.
Buffer make_buffer(const void* data, std::size_t bytes);

// Triangles in GPU buffers: interleaved float vertices, attribute i being `attribute_sizes[i]`
// consecutive floats, and three indices per triangle. draw() binds its vertex array only for
// the draw: the full-screen passes rely on the context's empty one (GlContext).
class IndexedMesh {
 public:
  IndexedMesh(std::span<const float> vertices, std::initializer_list<int> attribute_sizes,
              std::span<const GLuint> indices);
  void draw() const;
  bool empty() const { return index_count_ == 0; }

 private:
  Buffer vertices_, indices_;
  VertexArray vao_;
  GLsizei index_count_ = 0;
};

// A 2D texture with `levels` mip levels, nearest filtering, clamped to edge.
Texture make_texture(GLenum internal_format, int width, int height, int levels = 1);

// A framebuffer drawing to the given colour attachments (level 0 unless given) and an
// optional depth texture; throws if incomplete.
Framebuffer make_framebuffer(std::initializer_list<GLuint> colour, GLuint depth = 0, int level = 0);

// Links a program from the embedded shader files named, e.g. {"fullscreen.vert", "sao.frag"}.
// `defines` is inserted after the #version line. Throws with the compiler log on error.
Program make_program(std::initializer_list<const char*> files, const std::string& defines = {});

// Throws std::runtime_error naming `what` if GL reported an error.
void check_gl(const char* what);

}  // namespace aosuite::renderer

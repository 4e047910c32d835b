#include "renderer/gl/gl_objects.hpp"

#include <algorithm>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "renderer/passes/shader_library.hpp"

namespace aosuite::renderer {

void delete_texture(GLuint id) { glDeleteTextures(1, &id); }
void delete_framebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void delete_program(GLuint id) { glDeleteProgram(id); }
void delete_buffer(GLuint id) { glDeleteBuffers(1, &id); }
void delete_vertex_array(GLuint id) { glDeleteVertexArrays(1, &id); }
void delete_query(GLuint id) { glDeleteQueries(1, &id); }

void check_gl(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    throw std::runtime_error(std::string("OpenGL error 0x") + std::to_string(e) + " in " + what);
  }
}

Buffer make_buffer(const void* data, std::size_t bytes) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  glNamedBufferStorage(id, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 4)), data,
                       data ? 0 : GL_DYNAMIC_STORAGE_BIT);
  return Buffer(id);
}

IndexedMesh::IndexedMesh(std::span<const float> vertices,
                         std::initializer_list<int> attribute_sizes,
                         std::span<const GLuint> indices)
    : vertices_(make_buffer(vertices.empty() ? nullptr : vertices.data(), vertices.size_bytes())),
      indices_(make_buffer(indices.empty() ? nullptr : indices.data(), indices.size_bytes())),
      index_count_(static_cast<GLsizei>(indices.size())) {
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  vao_ = VertexArray(vao);
  int stride = 0;
  for (int size : attribute_sizes) stride += size;
  glVertexArrayVertexBuffer(vao, 0, vertices_.get(), 0,
                            static_cast<GLsizei>(stride * static_cast<int>(sizeof(float))));
  glVertexArrayElementBuffer(vao, indices_.get());
  GLuint index = 0, offset = 0;
  for (int size : attribute_sizes) {
    glEnableVertexArrayAttrib(vao, index);
    glVertexArrayAttribFormat(vao, index, size, GL_FLOAT, GL_FALSE, offset);
    glVertexArrayAttribBinding(vao, index, 0);
    ++index, offset += static_cast<GLuint>(static_cast<std::size_t>(size) * sizeof(float));
  }
  check_gl("mesh upload");
}

void IndexedMesh::draw() const {
  if (index_count_ == 0) return;
  GLint previous = 0;
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &previous);
  glBindVertexArray(vao_.get());
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(static_cast<GLuint>(previous));
}

Texture make_texture(GLenum internal_format, int width, int height, int levels) {
  GLuint id = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &id);
  Texture t(id);
  glTextureStorage2D(id, levels, internal_format, width, height);
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER,
                      levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  check_gl("make_texture");
  return t;
}

Framebuffer make_framebuffer(std::initializer_list<GLuint> colour, GLuint depth, int level) {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  Framebuffer fb(id);
  std::vector<GLenum> buffers;
  for (GLuint tex : colour) {
    const auto attachment = static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + buffers.size());
    glNamedFramebufferTexture(id, attachment, tex, level);
    buffers.push_back(attachment);
  }
  glNamedFramebufferDrawBuffers(id, static_cast<GLsizei>(buffers.size()), buffers.data());
  if (depth) glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth, 0);
  if (glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw std::runtime_error("incomplete framebuffer");
  }
  return fb;
}

namespace {

GLuint compile(const char* file, const std::string& defines) {
  std::string src = shader_text(file);
  // GLSL has no #include: splice the named shared files in, once each.
  for (std::size_t at; (at = src.find("#include \"")) != std::string::npos;) {
    const std::size_t end = src.find('"', at + 10);
    const std::string name = src.substr(at + 10, end - at - 10);
    src.replace(at, end + 1 - at, shader_text(name));
  }
  const std::size_t eol = src.find('\n');  // after "#version 450 core"
  src.insert(eol + 1, defines);
  const std::string_view name(file);
  const GLenum type = name.ends_with(".vert")   ? GL_VERTEX_SHADER
                      : name.ends_with(".comp") ? GL_COMPUTE_SHADER
                                                : GL_FRAGMENT_SHADER;
  const GLuint s = glCreateShader(type);
  const char* text = src.c_str();
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    std::vector<char> log(8192);
    glGetShaderInfoLog(s, static_cast<GLsizei>(log.size()), nullptr, log.data());
    glDeleteShader(s);
    throw std::runtime_error(std::string("shader ") + file + ": " + log.data());
  }
  return s;
}

}  // namespace

Program make_program(std::initializer_list<const char*> files, const std::string& defines) {
  Program p(glCreateProgram());
  std::vector<GLuint> shaders;
  for (const char* f : files) {
    shaders.push_back(compile(f, defines));
    glAttachShader(p.get(), shaders.back());
  }
  glLinkProgram(p.get());
  for (GLuint s : shaders) glDeleteShader(s);
  GLint ok = 0;
  glGetProgramiv(p.get(), GL_LINK_STATUS, &ok);
  if (!ok) {
    std::vector<char> log(8192);
    glGetProgramInfoLog(p.get(), static_cast<GLsizei>(log.size()), nullptr, log.data());
    throw std::runtime_error(std::string("program link: ") + log.data());
  }
  return p;
}

}  // namespace aosuite::renderer

// The OpenGL 4.5 entry points (direct state access, glClipControl, ...) that libOSMesa does
// not export as symbols: each is resolved once through OSMesaGetProcAddress and forwarded.
// Everything older is exported by libOSMesa itself.
#include "renderer/gl.hpp"
// after gl.h
#include <GL/osmesa.h>

#include <cstdio>
#include <cstdlib>

namespace {

template <class Fn>
Fn resolve(const char* name) {
  auto fn = reinterpret_cast<Fn>(OSMesaGetProcAddress(name));
  if (!fn) {
    std::fprintf(stderr, "aosuite: this Mesa lacks %s (OpenGL 4.5 is required)\n", name);
    std::abort();
  }
  return fn;
}

}  // namespace

#define FORWARD(ret, name, params, args)                  \
  extern "C" ret name params {                            \
    static const auto fn = resolve<ret(*) params>(#name); \
    return fn args;                                       \
  }

FORWARD(void, glBindTextureUnit, (GLuint unit, GLuint texture), (unit, texture))
FORWARD(GLenum, glCheckNamedFramebufferStatus, (GLuint fb, GLenum target), (fb, target))
FORWARD(void, glClearNamedBufferData,
        (GLuint buf, GLenum format_internal, GLenum format, GLenum type, const void* data),
        (buf, format_internal, format, type, data))
FORWARD(void, glClearNamedFramebufferfv,
        (GLuint fb, GLenum buffer, GLint draw, const GLfloat* value), (fb, buffer, draw, value))
FORWARD(void, glClipControl, (GLenum origin, GLenum depth), (origin, depth))
FORWARD(void, glCreateBuffers, (GLsizei n, GLuint* ids), (n, ids))
FORWARD(void, glCreateFramebuffers, (GLsizei n, GLuint* ids), (n, ids))
FORWARD(void, glCreateQueries, (GLenum target, GLsizei n, GLuint* ids), (target, n, ids))
FORWARD(void, glCreateTextures, (GLenum target, GLsizei n, GLuint* ids), (target, n, ids))
FORWARD(void, glCreateVertexArrays, (GLsizei n, GLuint* ids), (n, ids))
FORWARD(void, glEnableVertexArrayAttrib, (GLuint vao, GLuint index), (vao, index))
FORWARD(void, glGetNamedBufferSubData, (GLuint buf, GLintptr offset, GLsizeiptr size, void* data),
        (buf, offset, size, data))
FORWARD(void, glGetQueryObjectui64v, (GLuint id, GLenum pname, GLuint64* params),
        (id, pname, params))
FORWARD(void, glGetTextureImage,
        (GLuint tex, GLint level, GLenum format, GLenum type, GLsizei size, void* pixels),
        (tex, level, format, type, size, pixels))
FORWARD(void, glNamedBufferStorage,
        (GLuint buf, GLsizeiptr size, const void* data, GLbitfield flags), (buf, size, data, flags))
FORWARD(void, glNamedFramebufferDrawBuffers, (GLuint fb, GLsizei n, const GLenum* bufs),
        (fb, n, bufs))
FORWARD(void, glNamedFramebufferTexture, (GLuint fb, GLenum attachment, GLuint tex, GLint level),
        (fb, attachment, tex, level))
FORWARD(void, glTextureParameteri, (GLuint tex, GLenum pname, GLint param), (tex, pname, param))
FORWARD(void, glTextureStorage2D, (GLuint tex, GLsizei levels, GLenum format, GLsizei w, GLsizei h),
        (tex, levels, format, w, h))
FORWARD(void, glVertexArrayAttribBinding, (GLuint vao, GLuint attrib, GLuint binding),
        (vao, attrib, binding))
FORWARD(void, glVertexArrayAttribFormat,
        (GLuint vao, GLuint attrib, GLint size, GLenum type, GLboolean normalized, GLuint offset),
        (vao, attrib, size, type, normalized, offset))
FORWARD(void, glVertexArrayElementBuffer, (GLuint vao, GLuint buffer), (vao, buffer))
FORWARD(void, glVertexArrayVertexBuffer,
        (GLuint vao, GLuint binding, GLuint buffer, GLintptr offset, GLsizei stride),
        (vao, binding, buffer, offset, stride))

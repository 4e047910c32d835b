// OpenGL 4.5 core, reached through a table of entry points that the context's backend fills
// (eglGetProcAddress or OSMesaGetProcAddress): no GL library is linked, so EGL and OSMesa,
// which both export gl* symbols of their own, can share one build. An entry point missing
// from the list below is a compile error.
#pragma once

#include <GL/glcorearb.h>  // types and enums only: GL_GLEXT_PROTOTYPES is not defined

// X(pointer type, name) for every entry point the renderer calls.
#define AOSUITE_GL_ENTRY_POINTS(X)                                       \
  X(PFNGLATTACHSHADERPROC, glAttachShader)                               \
  X(PFNGLBEGINQUERYPROC, glBeginQuery)                                   \
  X(PFNGLBINDBUFFERPROC, glBindBuffer)                                   \
  X(PFNGLBINDBUFFERBASEPROC, glBindBufferBase)                           \
  X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                         \
  X(PFNGLBINDIMAGETEXTUREPROC, glBindImageTexture)                       \
  X(PFNGLBINDTEXTUREUNITPROC, glBindTextureUnit)                         \
  X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                         \
  X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, glCheckNamedFramebufferStatus) \
  X(PFNGLCLEARBUFFERFVPROC, glClearBufferfv)                             \
  X(PFNGLCLEARBUFFERUIVPROC, glClearBufferuiv)                           \
  X(PFNGLCLEARNAMEDBUFFERDATAPROC, glClearNamedBufferData)               \
  X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, glClearNamedFramebufferfv)         \
  X(PFNGLCLEARTEXIMAGEPROC, glClearTexImage)                             \
  X(PFNGLCLIPCONTROLPROC, glClipControl)                                 \
  X(PFNGLCOMPILESHADERPROC, glCompileShader)                             \
  X(PFNGLCOPYIMAGESUBDATAPROC, glCopyImageSubData)                       \
  X(PFNGLCREATEBUFFERSPROC, glCreateBuffers)                             \
  X(PFNGLCREATEFRAMEBUFFERSPROC, glCreateFramebuffers)                   \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                             \
  X(PFNGLCREATEQUERIESPROC, glCreateQueries)                             \
  X(PFNGLCREATESHADERPROC, glCreateShader)                               \
  X(PFNGLCREATETEXTURESPROC, glCreateTextures)                           \
  X(PFNGLCREATEVERTEXARRAYSPROC, glCreateVertexArrays)                   \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                             \
  X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                   \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                             \
  X(PFNGLDELETEQUERIESPROC, glDeleteQueries)                             \
  X(PFNGLDELETESHADERPROC, glDeleteShader)                               \
  X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                           \
  X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)                   \
  X(PFNGLDEPTHFUNCPROC, glDepthFunc)                                     \
  X(PFNGLDEPTHMASKPROC, glDepthMask)                                     \
  X(PFNGLDISABLEPROC, glDisable)                                         \
  X(PFNGLDISPATCHCOMPUTEPROC, glDispatchCompute)                         \
  X(PFNGLDRAWARRAYSPROC, glDrawArrays)                                   \
  X(PFNGLDRAWELEMENTSPROC, glDrawElements)                               \
  X(PFNGLENABLEPROC, glEnable)                                           \
  X(PFNGLENABLEVERTEXARRAYATTRIBPROC, glEnableVertexArrayAttrib)         \
  X(PFNGLENDQUERYPROC, glEndQuery)                                       \
  X(PFNGLFINISHPROC, glFinish)                                           \
  X(PFNGLFLUSHPROC, glFlush)                                             \
  X(PFNGLGETERRORPROC, glGetError)                                       \
  X(PFNGLGETINTEGERVPROC, glGetIntegerv)                                 \
  X(PFNGLGETACTIVEUNIFORMSIVPROC, glGetActiveUniformsiv)                 \
  X(PFNGLGETNAMEDBUFFERSUBDATAPROC, glGetNamedBufferSubData)             \
  X(PFNGLGETUNIFORMINDICESPROC, glGetUniformIndices)                     \
  X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                     \
  X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                               \
  X(PFNGLGETQUERYOBJECTUI64VPROC, glGetQueryObjectui64v)                 \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                       \
  X(PFNGLGETSHADERIVPROC, glGetShaderiv)                                 \
  X(PFNGLGETSTRINGPROC, glGetString)                                     \
  X(PFNGLGETTEXTUREIMAGEPROC, glGetTextureImage)                         \
  X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)                   \
  X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                 \
  X(PFNGLMEMORYBARRIERPROC, glMemoryBarrier)                             \
  X(PFNGLNAMEDBUFFERSTORAGEPROC, glNamedBufferStorage)                   \
  X(PFNGLNAMEDBUFFERSUBDATAPROC, glNamedBufferSubData)                   \
  X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, glNamedFramebufferDrawBuffers) \
  X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, glNamedFramebufferTexture)         \
  X(PFNGLPIXELSTOREIPROC, glPixelStorei)                                 \
  X(PFNGLPROGRAMUNIFORM1FPROC, glProgramUniform1f)                       \
  X(PFNGLPROGRAMUNIFORM1IPROC, glProgramUniform1i)                       \
  X(PFNGLPROGRAMUNIFORM2FPROC, glProgramUniform2f)                       \
  X(PFNGLPROGRAMUNIFORM2IPROC, glProgramUniform2i)                       \
  X(PFNGLPROGRAMUNIFORMMATRIX4FVPROC, glProgramUniformMatrix4fv)         \
  X(PFNGLSHADERSOURCEPROC, glShaderSource)                               \
  X(PFNGLTEXTUREPARAMETERIPROC, glTextureParameteri)                     \
  X(PFNGLTEXTURESTORAGE2DPROC, glTextureStorage2D)                       \
  X(PFNGLTEXTURESUBIMAGE2DPROC, glTextureSubImage2D)                     \
  X(PFNGLUSEPROGRAMPROC, glUseProgram)                                   \
  X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, glVertexArrayAttribBinding)       \
  X(PFNGLVERTEXARRAYATTRIBFORMATPROC, glVertexArrayAttribFormat)         \
  X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, glVertexArrayElementBuffer)       \
  X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, glVertexArrayVertexBuffer)         \
  X(PFNGLVIEWPORTPROC, glViewport)

namespace aosuite::renderer {

// The entry points, named as GL names them, so code in this namespace calls glFoo(...) as
// usual; as namespaced variables they never clash with the gl* functions a driver exports.
#define AOSUITE_GL_DECLARE(type, name) extern type name;
AOSUITE_GL_ENTRY_POINTS(AOSUITE_GL_DECLARE)
#undef AOSUITE_GL_DECLARE

// Resolves a GL entry point by name for the current context's backend.
using GlGetProcAddress = void* (*)(const char* name);
// Fills the table; throws std::runtime_error naming the first entry point the driver lacks.
void load_gl_entry_points(GlGetProcAddress get_proc);

}  // namespace aosuite::renderer

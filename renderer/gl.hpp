// OpenGL 4.5 core entry points. Mesa's libOSMesa exports them directly, so no loader is
// needed; an EGL backend would bring its own libOpenGL with the same prototypes.
#pragma once

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>

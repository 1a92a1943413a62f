#pragma once
// The OpenGL API the demo draws with: OpenGL 3.3 core on the desktop (Mesa's
// libGL exports its entry points; the demo's target defines
// GL_GLEXT_PROTOTYPES so that <GL/gl.h> declares them), OpenGL ES 3.0 in the
// browser (WebGL 2 through Emscripten).
#ifdef __EMSCRIPTEN__
#include <GLES3/gl3.h>
#else
#include <GL/gl.h>
#include <GL/glext.h>
#endif


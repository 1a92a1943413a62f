#pragma once
// The page's stand-in for <GL/freeglut.h>: Emscripten's GLUT has freeglut's
// standard API (<GL/glut.h>) but not the extensions that the demo and Dear
// ImGui's GLUT backend name. Here they do what a browser allows: the wheel
// comes as buttons 3 and 4 (main.cpp turns them into wheel turns); the
// browser runs the main loop, which ends when the App says so (main.cpp); a
// key held down repeats (the App ignores a repeated space itself;
// glutIgnoreKeyRepeat, declared by Emscripten but not defined, is page.cpp's); the
// canvas's context is WebGL 2 whatever version is asked for (the build's
// -sMIN_WEBGL_VERSION=2).
#include <GL/glut.h>

#define GLUT_ACTION_ON_WINDOW_CLOSE 0x01F9
#define GLUT_ACTION_GLUTMAINLOOP_RETURNS 1
#define GLUT_CORE_PROFILE 0x0001

static inline void glutMouseWheelFunc(void (*)(int, int, int, int)) {}
static inline void glutLeaveMainLoop() {}
static inline void glutSetOption(int, int) {}
static inline void glutInitContextVersion(int, int) {}
static inline void glutInitContextProfile(int) {}
// One window, so one slot.
static inline void*& glutWindowDataSlot() {
  static void* data = nullptr;
  return data;
}
static inline void glutSetWindowData(void* data) { glutWindowDataSlot() = data; }
static inline void* glutGetWindowData() { return glutWindowDataSlot(); }

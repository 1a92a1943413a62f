// particle-demo: options, the GLUT window, and callbacks that forward to the
// one App (reached through the window's user data, not a global).
#include <GL/freeglut.h>
#include <imgui.h>

#include <cstdio>
#include <stdexcept>

#include "app.h"
#include "backends/imgui_impl_glut.h"

namespace {

demo::App& app() { return *static_cast<demo::App*>(glutGetWindowData()); }

// ImGui sees every event first; the App gets keys unless a text field is
// being edited, and presses unless they land on an ImGui window. Releases
// always reach the App so a drag never sticks.
void onKeyboard(unsigned char key, int x, int y) {
  ImGui_ImplGLUT_KeyboardFunc(key, x, y);
  if (!ImGui::GetIO().WantTextInput) app().keyboard(key);
}
void onKeyboardUp(unsigned char key, int x, int y) { ImGui_ImplGLUT_KeyboardUpFunc(key, x, y); }
void onSpecial(int key, int x, int y) { ImGui_ImplGLUT_SpecialFunc(key, x, y); }
void onSpecialUp(int key, int x, int y) { ImGui_ImplGLUT_SpecialUpFunc(key, x, y); }
void onMouse(int button, int state, int x, int y) {
  ImGui_ImplGLUT_MouseFunc(button, state, x, y);
  if (state == GLUT_UP || !ImGui::GetIO().WantCaptureMouse)
    app().mouse(button, state, x, y, (glutGetModifiers() & GLUT_ACTIVE_SHIFT) != 0);
}
void onMotion(int x, int y) {
  ImGui_ImplGLUT_MotionFunc(x, y);
  app().motion(x, y);
}
void onPassiveMotion(int x, int y) { ImGui_ImplGLUT_MotionFunc(x, y); }
void onWheel(int button, int direction, int x, int y) { ImGui_ImplGLUT_MouseWheelFunc(button, direction, x, y); }
void onReshape(int width, int height) { app().reshape(width, height); }
void onDisplay() { app().display(); }

// The frame clock. Interactive: about 60 frames per second. Scripted runs
// (--frames, --script): as fast as possible.
void onTimer(int) {
  app().requestFrame();
  glutPostRedisplay();
  // The next tick of a 60 Hz grid since glutInit, so frames average 60 per
  // second (a fixed 16 ms delay would give 62.5, and drift).
  // Tick k is due at ceil(1000 k / 60) ms; schedule the first one after now.
  const int now = glutGet(GLUT_ELAPSED_TIME);
  auto tickTime = [](int k) { return (1000 * k + 59) / 60; };
  int k = now * 60 / 1000 + 1;
  while (tickTime(k) <= now) ++k;
  glutTimerFunc(static_cast<unsigned>(tickTime(k) - now), onTimer, 0);
}
void onIdle() {
  app().requestFrame();
  glutPostRedisplay();
}

}  // namespace

int main(int argc, char** argv) {
  const demo::DemoOptions options = demo::parseOptions(argc, argv);
  std::unique_ptr<demo::App> application;
  try {
    application = std::make_unique<demo::App>(options);
  } catch (const std::exception& e) {
    demo::reportBadUsage(e.what());
    return demo::exitBadUsage;
  }

  glutInit(&argc, argv);
  glutInitDisplayMode(GLUT_RGBA | GLUT_DOUBLE);
  glutInitWindowSize(options.windowWidth, options.windowHeight);
  glutSetOption(GLUT_ACTION_ON_WINDOW_CLOSE, GLUT_ACTION_GLUTMAINLOOP_RETURNS);
  glutCreateWindow("particle-lab demo");
  glutSetWindowData(application.get());
  application->initGraphics();

  glutDisplayFunc(onDisplay);
  glutReshapeFunc(onReshape);
  glutKeyboardFunc(onKeyboard);
  glutKeyboardUpFunc(onKeyboardUp);
  glutSpecialFunc(onSpecial);
  glutSpecialUpFunc(onSpecialUp);
  glutMouseFunc(onMouse);
  glutMotionFunc(onMotion);
  glutPassiveMotionFunc(onPassiveMotion);
  glutMouseWheelFunc(onWheel);
  if ((options.frames || !options.script.empty()) && !options.realtime) glutIdleFunc(onIdle);
  else glutTimerFunc(16, onTimer, 0);

  glutMainLoop();
  application->writeStateLog();
  return 0;
}

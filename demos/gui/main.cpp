// particle-demo: options, the GLUT window, and callbacks that forward to the
// one App (reached through the window's user data, not a global).
#include <GL/freeglut.h>
#include <imgui.h>

#include <cstdio>
#include <new>
#include <stdexcept>
#include <string>

#include "app.h"
#include "backends/imgui_impl_glut.h"
#include "options/thread_option.h"
#include "particles/threads.h"

namespace {

demo::App& app() { return *static_cast<demo::App*>(glutGetWindowData()); }

// No exception may leave a GLUT callback (it would end the program through
// std::terminate): the App catches its actions' errors, and anything left
// is shown here and the demo runs on.
template <class Callback>
void guarded(Callback&& callback) {
  try {
    callback();
  } catch (const std::bad_alloc&) {
    app().showError("out of memory");
  } catch (const std::exception& e) {
    app().showError(e.what());
  } catch (...) {
    app().showError("unknown error");
  }
}

bool shiftHeld() { return (glutGetModifiers() & GLUT_ACTIVE_SHIFT) != 0; }

void onKeyboard(unsigned char key, int, int) { guarded([&] { app().inputKey(key); }); }
void onKeyboardUp(unsigned char key, int x, int y) {
  ImGui_ImplGLUT_KeyboardUpFunc(key, x, y);
  guarded([&] { app().inputKeyUp(key); });
}
void onSpecial(int key, int x, int y) { ImGui_ImplGLUT_SpecialFunc(key, x, y); }
void onSpecialUp(int key, int x, int y) { ImGui_ImplGLUT_SpecialUpFunc(key, x, y); }
void onMouse(int button, int state, int x, int y) {
  // freeglut reports the wheel as buttons 3 and 4 when no wheel callback takes it.
  const bool shift = shiftHeld();
  guarded([&] { app().inputMouse(button, state, x, y, shift); });
}
void onMotion(int x, int y) { guarded([&] { app().inputMotion(x, y); }); }
void onPassiveMotion(int x, int y) { guarded([&] { app().inputPassiveMotion(x, y); }); }
void onWheel(int, int direction, int x, int y) { guarded([&] { app().inputWheel(direction, x, y); }); }
void onReshape(int width, int height) { guarded([&] { app().reshape(width, height); }); }
void onDisplay() { guarded([&] { app().display(); }); }

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
  std::string threadsNote;
  particles::setThreadCount(options::threadsWithinAffinity(options.threads, threadsNote));
  if (!threadsNote.empty()) std::fprintf(stderr, "particle-demo: note: %s\n", threadsNote.c_str());
  std::unique_ptr<demo::App> application;
  try {
    application = std::make_unique<demo::App>(options);
  } catch (const std::bad_alloc&) {
    demo::reportBadUsage("out of memory building the scene");
    return demo::exitBadUsage;
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
  glutIgnoreKeyRepeat(1);  // a held space is one press (space + drag pans)
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
  if (!options.paced()) glutIdleFunc(onIdle);
  else glutTimerFunc(16, onTimer, 0);

  glutMainLoop();
  const bool written = application->writeStateLog() && !application->outputsFailed();
  return written ? 0 : demo::exitOutputFailed;
}

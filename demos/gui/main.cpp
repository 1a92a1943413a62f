// particle-demo: options, the GLUT window, and callbacks that forward to the
// one App (reached through the window's user data, not a global). The same
// file runs the page (Emscripten's GLUT, web/GL/freeglut.h): there the
// browser owns the main loop, and the page hears when the demo ends (web/page.h).
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
#ifdef __EMSCRIPTEN__
#include "page.h"
#endif

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
  // freeglut reports the wheel as buttons 3 and 4 when no wheel callback
  // takes it (Emscripten's GLUT always does): a press is a turn.
  if (button == 3 || button == 4) {
#ifdef __EMSCRIPTEN__
    // Emscripten 3.1.6's GLUT reads the browser's legacy mousewheel event
    // (wheelDelta > 0 away from the user) as if it were a wheel event's
    // deltaY, whose sign is the other way: its button 4 is the wheel turned up.
    const int up = 4;
#else
    const int up = 3;
#endif
    if (state == GLUT_DOWN) guarded([&] { app().inputWheel(button == up ? 1 : -1, x, y); });
    return;
  }
  const bool shift = shiftHeld();
  guarded([&] { app().inputMouse(button, state, x, y, shift); });
}
void onMotion(int x, int y) { guarded([&] { app().inputMotion(x, y); }); }
void onPassiveMotion(int x, int y) { guarded([&] { app().inputPassiveMotion(x, y); }); }
void onWheel(int, int direction, int x, int y) { guarded([&] { app().inputWheel(direction, x, y); }); }
void onReshape(int width, int height) { guarded([&] { app().reshape(width, height); }); }

// After the main loop: the state log (--log-state) and the exit code.
int finish(demo::App& application) {
  const bool written = application.writeStateLog() && !application.outputsFailed();
  return written ? 0 : demo::exitOutputFailed;
}

void onDisplay() {
  guarded([&] { app().display(); });
#ifdef __EMSCRIPTEN__
  web::frameDrawn();
  // The browser's loop never returns to main: the demo ends here, once.
  static bool ended = false;
  if (app().quitRequested() && !ended) {
    ended = true;
    web::finished(finish(app()));
  }
#endif
}

// The frame clock. Interactive: about 60 frames per second. Scripted runs
// (--frames, --script): as fast as possible.
void onTimer(int) {
  if (app().quitRequested()) return;
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
  if (app().quitRequested()) return;
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
  // The scene's shaders and ImGui's OpenGL3 backend (painter.h).
  glutInitContextVersion(3, 3);
  glutInitContextProfile(GLUT_CORE_PROFILE);
  glutInitWindowSize(options.windowWidth, options.windowHeight);
  glutSetOption(GLUT_ACTION_ON_WINDOW_CLOSE, GLUT_ACTION_GLUTMAINLOOP_RETURNS);
  glutCreateWindow("particle-lab demo");
  glutSetWindowData(application.get());
#ifdef __EMSCRIPTEN__
  web::attach(*application);
#endif
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

#ifdef __EMSCRIPTEN__
  // The browser runs the loop: glutMainLoop leaves main without returning,
  // and the App lives on with the page.
  application.release();
  glutMainLoop();
  return 0;
#else
  glutMainLoop();
  return finish(*application);
#endif
}

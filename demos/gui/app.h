#pragma once
// The application object that every GLUT callback reaches: the panes being
// simulated, the user's input, and one frame = input → step → draw → output.
#include <memory>
#include <string>
#include <vector>

#include "options.h"
#include "state_log.h"
#include "renderer.h"
#include "scene_keys.h"
#include "script.h"
#include "simulation.h"
#include "view.h"

namespace demo {

// What the left or right mouse button is doing.
enum class MouseTool {
  None,
  Drag,  // a mouse spring pulls the grabbed particle toward the cursor
  Pin,   // the particle is pinned and follows the cursor; a click on a pinned one unpins it
};

// Mouse-spring settings from the panel; damping defaults to critical for the
// grabbed mass, k_d = 2√(k_s m).
struct MouseSpringSettings {
  double stiffness = 5.0;   // k_s, force / length
  bool criticalDamping = true;
  double damping = 0.0;     // k_d when not critical, force / speed
  double pickPixels = 16;   // a press farther than this from every particle grabs nothing
};

class App {
 public:
  // Builds the first scene and reads the script: throws std::invalid_argument
  // for a bad scene, parameter, integrator or script. Touches no OpenGL.
  explicit App(DemoOptions options);
  ~App();

  // Needs a current GL context: sets up ImGui.
  void initGraphics();

  // --- the GLUT-facing handlers (scripted events call the same ones) --------
  void keyboard(unsigned char key);
  void mouse(int button, int state, int x, int y, bool shift);
  void motion(int x, int y);
  void reshape(int width, int height);
  // Called by the frame clock (a 60 Hz timer, or idle in scripted runs): the
  // next display() is a new frame.
  void requestFrame() { frameDue_ = true; }
  // One frame when one is due: scripted input, stepping, drawing, and the
  // outputs of the last frame. Otherwise (an expose, a resize) it only redraws,
  // so extra redisplays never speed up the simulation.
  void display();

  bool quitRequested() const { return quit_; }
  // Written at exit (also after q/Esc): --log-state.
  void writeStateLog() const;

 private:
  // --- frame phases -------------------------------------------------------
  void playScript();
  void advance();
  void draw();
  void drawHud();
  void drawPaneLines();
  void drawForceLegend();
  void drawHelp();
  void drawDivergenceMessages();
  void drawPanel();
  void finishFrame();

  // --- actions ------------------------------------------------------------
  void loadScene(const SceneChoice& choice, bool keepIntegrators);
  void resetScene();
  void setPaneCount(int count);
  void cycleIntegrators();
  void scaleDt(double factor);
  void rewind();
  void setStatus(const std::string& text);
  // The rest of the keys' actions, one each.
  void doubleDt() { scaleDt(2.0); }
  void halveDt() { scaleDt(0.5); }
  void togglePause() { paused_ = !paused_; }
  void stepOnce() { paused_ = true; stepRequested_ = true; }
  void toggleForces() { drawOptions_.forces = !drawOptions_.forces; }
  void toggleConstraints() { drawOptions_.constraints = !drawOptions_.constraints; }
  void toggleHelp() { showHelp_ = !showHelp_; }
  void togglePanel() { showPanel_ = !showPanel_; }
  void toggleLockstep();
  void cyclePaneCount() { setPaneCount(panes_.size() >= 4 ? 1 : static_cast<int>(panes_.size()) + 1); }
  void requestQuit() { quit_ = true; }

  // Every key besides the scene keys: what the help overlay lists and what
  // keyboard() dispatches, from one table.
  struct KeyBinding {
    const char* keys;   // the characters that trigger it
    const char* label;  // as the help shows the keys
    const char* help;
    void (App::*action)();
  };
  static const std::vector<KeyBinding>& keyBindings();

  // --- layout -------------------------------------------------------------
  PixelRect worldArea() const;
  std::vector<ViewTransform> paneViews() const;
  int paneAt(int x, int y) const;  // −1 outside every pane

  DemoOptions options_;
  SceneChoice scene_;
  std::vector<std::unique_ptr<Simulation>> panes_;
  std::vector<ScriptEvent> script_;
  std::size_t nextScriptEvent_ = 0;
  Renderer renderer_;

  StepMode stepMode_ = StepMode::FixedTime;
  double speed_ = 1.0;  // simulated seconds per real second (frames at 60 per second)
  bool paused_ = false;
  bool stepRequested_ = false;
  DrawOptions drawOptions_;
  bool showHelp_ = false;
  bool showPanel_ = true;
  MouseSpringSettings springSettings_;

  MouseTool tool_ = MouseTool::None;
  int toolParticle_ = -1;
  int toolPane_ = -1;
  bool pinWasPinned_ = false, pinMoved_ = false;
  int pressX_ = 0, pressY_ = 0;  // where the tool started, pixels

  int windowWidth_, windowHeight_;
  long long frame_ = 0;
  double drawMs_ = 0.0;
  std::vector<Overlay> overlays_;  // the text drawn over the panes in the last frame  // wall time of the last frame's scene drawing, GL work included
  std::string status_;
  int statusFrames_ = 0;
  bool quit_ = false;
  bool frameDue_ = false;
  bool imguiReady_ = false;
};

}  // namespace demo

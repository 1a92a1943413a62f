#pragma once
// The application object that every GLUT callback reaches: the panes being
// simulated, the user's input, and one frame = input → step → draw → output.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "real_time.h"
#include "advice_job.h"
#include "build_mode.h"
#include "camera.h"
#include "exact_motion.h"
#include "frame_budget.h"
#include "layout.h"
#include "options.h"
#include "state_log.h"
#include "renderer.h"
#include "scene_keys.h"
#include "script.h"
#include "simulation.h"
#include "text_layout.h"
#include "view.h"

namespace demo {

// What the left or right mouse button is doing.
enum class MouseTool {
  None,
  Drag,  // a mouse spring pulls the grabbed particle toward the cursor
  Pin,   // the particle is pinned and follows the cursor; a click on a pinned one unpins it
};

// Mouse settings from the panel and --grab: the joint (frequency, damping
// ratio and stiffness ratio, applied to what the grabbed particle pulls,
// particles/grab.h) and the reach.
struct MouseSettings {
  particles::MouseJointSettings joint;
  double pickPixels = 16;  // a press farther than this from every particle grabs nothing
};

// The wind and tearing that keys w and t switch and the panel sets
// (wind_panel.cpp), applied to every pane alike. The wind blows on the
// scene's wind edges (the cloth's sides, the hair's links).
struct WindTearControls {
  bool windOn = false;
  particles::WindSettings wind = [] {
    particles::WindSettings w;  // a 5 m/s gusty wind to the right: the cloth leans some 25°
    w.speed = 5.0;
    w.drag = 0.02;
    w.gust = 0.5;
    return w;
  }();
  bool tearOn = false;
  double tearStrain = 0.5;  // springs stretched by half their rest length tear
};

// An opaque rectangle under the bars' text or the panel, filled by a clear
// before ImGui draws on it (App::draw): drawn as ImGui's triangles, these were
// nine tenths of the pixels its draw lists cover, each one textured and
// blended by a software rasteriser.
struct Backdrop {
  PixelRect rect;
  Rgb colour;
};

class App {
 public:
  // Builds the first scene and reads the script: throws std::invalid_argument
  // for a bad scene, parameter, integrator or script. Touches no OpenGL.
  explicit App(DemoOptions options);
  ~App();

  // Needs a current GL context: sets up ImGui.
  void initGraphics();

  // --- input: GLUT's callbacks and the script both call these -------------
  // Each goes to ImGui first, then to the demo unless ImGui takes it (a text
  // field being edited, a press on the panel). No exception leaves them: a
  // failed action shows its message and the demo runs on.
  void inputKey(unsigned char key);
  void inputKeyUp(unsigned char key);
  void inputMouse(int button, int state, int x, int y, bool shift);
  void inputMotion(int x, int y);         // with a button held
  void inputPassiveMotion(int x, int y);  // with no button held
  void inputWheel(int direction, int x, int y);
  void reshape(int width, int height);
  // Shows an error that escaped an action (GLUT's callbacks catch them too).
  void showError(const std::string& message);
  // Called by the frame clock (a 60 Hz timer, or idle in scripted runs): the
  // next display() is a new frame.
  void requestFrame() { frameDue_ = true; }
  // One frame when one is due: scripted input, stepping, drawing, and the
  // outputs of the last frame. Otherwise (an expose, a resize) it only redraws,
  // so extra redisplays never speed up the simulation.
  void display();

  bool quitRequested() const { return quit_; }
  // Written at exit (also after q/Esc): --log-state. False (with the message
  // on stderr) when an output could not be written.
  bool writeStateLog() const;
  bool outputsFailed() const { return outputFailed_; }

 private:
  // --- frame phases -------------------------------------------------------
  void playScript();
  void advance();
  void draw();
  void drawPanes(const std::vector<ViewTransform>& views);  // each pane's scene, ghost and drawing record
  void drawTopBar();
  std::string sceneSummary() const;   // the title's summary of the first pane's scene
  int particlesOutOfView() const;     // the first pane's particles outside its view
  void drawBottomBar();
  void drawPaneHeaders();
  void drawOutOfViewIndicators();
  void drawHelp();
  void drawPanel();
  // The panel's sections, top to bottom, and their parts.
  void drawSceneSection();
  void drawSceneCombo();
  void drawPresetCombo();
  void drawSceneParams();
  void drawRunButtons();
  void drawStateFile();
  void drawIntegrationSection();
  void drawPaneIntegrator(std::size_t pane);
  void drawIntegratorSettings();
  void drawTimeControls();
  void drawAdvicePanel();
  void drawAdviceRequest();
  void drawAdviceButtons(bool running);
  void drawAdviceResult();
  void drawPlotsSection();
  void drawSolverSection();
  void drawSolverSettings();
  void drawMouseSpringSettings();
  void drawWindTearSection();
  void drawDisplaySection();
  void recordWidget(const char* name);  // the last ImGui item, for scripted clicks
  // Build mode's section (build_panel.cpp) and its parts.
  void drawBuildSection();
  void drawBuildTools();
  void drawBuildFields(const char* target, const Json& object);
  void drawBuildHistory();
  void drawBuildFile();
  void drawBuildSelection();
  void drawBuildObjectList();
  void drawBuildOverlay(const ViewTransform& view);  // the selection, the gesture, the snap (build_draw.cpp)
  void finishFrame();

  // --- the demo's own handling of input ----------------------------------
  void keyboard(unsigned char key);
  void mouse(int button, int state, int x, int y, bool shift);
  void motion(int x, int y);
  void guarded(const std::function<void()>& action);

  // --- actions ------------------------------------------------------------
  void replacePanes(std::vector<std::unique_ptr<Simulation>> panes);  // and drops the mouse tool
  void loadScene(const SceneChoice& choice, bool keepIntegrators);
  void chooseScene(SceneChoice choice);
  void resetScene();
  void setPaneCount(int count);
  void cycleIntegrators();
  std::string compareLine() const;
  static std::string integratorLine(int index);
  void scaleDt(double factor);
  void rewind();
  void setStatus(const std::string& text);
  void setError(const std::string& text);
  void frameAll();
  void sceneView();  // the camera as the scene starts it; the scene runs on
  void startAdvice();
  void pollAdvice();
  void applyAdvice();
  bool adviceIsForThisScene() const;
  // Why a pane shows what it shows (overlay.cpp); brief: for the HUD and a
  // compare pane's header, with the top bar saying a divergence in full.
  std::string paneStateLine(const Simulation& sim, bool brief = false) const;
  // Wind and tearing (wind_panel.cpp): the controls taken from a new scene,
  // and pushed to every pane.
  void takeWindTearFromScene();
  void applyWindTear();
  void toggleWind();
  void toggleTearing();
  std::string realTimeReadout() const;
  std::string ghostLabel() const;
  // The rest of the keys' actions, one each.
  void doubleDt() { scaleDt(2.0); }
  void halveDt() { scaleDt(0.5); }
  void togglePause() { paused_ = !paused_; }
  void stepOnce() { paused_ = true; stepRequested_ = true; }
  void toggleForces() { drawOptions_.forces = !drawOptions_.forces; }
  void toggleConstraints() { drawOptions_.constraints = !drawOptions_.constraints; }
  void toggleGhost() { drawOptions_.ghost = !drawOptions_.ghost; }
  void toggleHelp() { showHelp_ = !showHelp_; }
  void togglePanel() { showPanel_ = !showPanel_; }
  void toggleLockstep();
  void cyclePaneCount() { setPaneCount(panes_.size() >= 4 ? 1 : static_cast<int>(panes_.size()) + 1); }
  void requestQuit() { quit_ = true; }
  void requestScreenshot() { screenshotRequested_ = true; }
  // The frame just drawn to --record's directory, and the screenshot the k key asked for.
  void writeFrameImages();
  void reportFailedWrite(const std::string& message);
  // The panel's state actions (state_actions.cpp): the state now to a scene
  // file and back, and recording on and off.
  void saveState();
  void loadState();
  void toggleRecording();
  std::string recordDirectory() const;

  // Every key besides the scene keys: what the help overlay lists and what
  // keyboard() dispatches, from one table.
  struct KeyBinding {
    const char* keys;   // the characters that trigger it
    const char* label;  // as the help shows the keys
    const char* help;
    void (App::*action)();
  };
  static const std::vector<KeyBinding>& keyBindings();

  // --- build mode (build_mode.h; build_actions.cpp) -------------------------
  // The scene on screen is built from the document being edited, paused at
  // t = 0; leaving build mode runs it. Every edit is committed through
  // commitBuild, which the scene-file reader checks before anything changes.
  void toggleBuildMode();
  void enterBuildMode(bool currentState);  // from the scene at t = 0, or as it is now
  void leaveBuildMode();
  bool buildKeyboard(unsigned char key);  // true when build mode took the key
  bool buildMouse(int button, int state, int x, int y);  // false: not build mode's (a pan)
  void buildMotion(int x, int y);
  void runBuildTool(const std::vector<BuildPoint>& points);
  void commitBuild(Json document, const std::string& what);
  void startBuildFrom(Json document, const std::string& what);
  void showBuildDocument();
  void showBuiltScene(scenes::Scene scene);
  void chooseBuildTool(std::size_t tool);
  void showBuildHint();
  double buildPickRadius() const;  // world units
  // target: "selected" (the selection, or the scene), "new" (the tool's fields
  // for what it adds) or "build" (grid, file); text as typed (parseFieldValue).
  void editBuildField(const std::string& target, const std::string& field, const std::string& text);
  void selectBuildObject(const std::optional<ObjectRef>& ref);
  void scriptBuildEvent(const ScriptEvent& event);
  void undoBuild();
  void redoBuild();
  void newBuild();
  void saveBuild();
  void openBuild();
  void deleteBuildSelection();
  void finishBuildClicks();
  static const std::vector<KeyBinding>& buildKeyBindings();

  // --- layout -------------------------------------------------------------
  Layout layout() const;
  std::vector<ViewTransform> paneViews() const;
  int paneAt(int x, int y) const;  // −1 outside every pane's world

  DemoOptions options_;
  SceneChoice scene_;
  std::vector<std::unique_ptr<Simulation>> panes_;
  std::vector<ScriptEvent> script_;
  std::size_t nextScriptEvent_ = 0;
  Renderer renderer_;

  StepMode stepMode_ = StepMode::FixedTime;
  double speed_ = 1.0;  // simulated seconds per real second (frames at 60 per second)
  FrameBudget lastBudget_;  // what the last frame's stepping budget did (frame_budget.h)
  BudgetTally budgetTally_;
  bool paused_ = false;
  bool stepRequested_ = false;
  DrawOptions drawOptions_;
  bool showHelp_ = false;
  bool showPanel_ = true;
  MouseSettings mouseSettings_;
  WindTearControls windTear_;
  Camera camera_;

  MouseTool tool_ = MouseTool::None;
  int toolParticle_ = -1;
  int toolPane_ = -1;
  bool pinWasPinned_ = false, pinMoved_ = false;
  int pressX_ = 0, pressY_ = 0;  // where the tool started, pixels
  bool panning_ = false;         // a middle-button or space + left drag moves the camera
  int panX_ = 0, panY_ = 0;      // the pointer at the last pan motion
  bool spaceHeld_ = false, spaceDragged_ = false;
  bool grabbedOnce_ = false;     // the first-run hint shows until a particle is dragged
  bool closePopups_ = false;     // Esc closes an open combo instead of quitting
  std::vector<unsigned char> scriptKeysDown_;  // scripted keys, released the next frame
  long long scriptHeldFrames_ = 0;  // frames a `wait` held the script: later events come this much later

  int windowWidth_, windowHeight_;
  long long frame_ = 0;
  // Wall times of the last frame's drawing, GL work included: the scene, and
  // the text and panel (ImGui) on top.
  // The drawing's time, measured on one frame in drawTimingPeriod (App::draw).
  static constexpr int drawTimingPeriod = 30;
  double sceneDrawMs_ = 0.0, overlayDrawMs_ = 0.0;
  // Every timed frame's two times after the first (which compiles the
  // shaders), for the state log's medians.
  std::vector<double> sceneDrawSamples_, overlayDrawSamples_;
  std::vector<Renderer::PaneDrawing> paneDrawings_;  // each pane's shaded faces in the last frame
  std::vector<Overlay> overlays_;  // the text and controls drawn in the last frame
  std::vector<Backdrop> backdrops_;  // the last frame's, under the bars' text and the panel
  std::map<std::string, WrappedText> barText_;  // each bar's text as laid out last (overlay.cpp)
  std::vector<Overlay> widgets_;   // the panel's buttons and combos, for scripted clicks
  // Wall time of every frame (input, stepping, drawing, swap) and its
  // stepping part, for the state log's frame-time summary.
  std::vector<double> frameMs_, frameSimulationMs_;
  std::string status_;
  bool statusIsError_ = false;
  int statusFrames_ = 0;
  bool screenshotRequested_ = false;
  bool recording_ = false;  // frames written to recordDirectory(): --record, or the panel's Record
  std::string stateFile_ = "state.json";  // the panel's Save state / Load state file
  ExactMotion exact_;              // the scene's closed form, drawn as a ghost; empty if none
  // When the mouse first moved or pinned a particle since the scene started:
  // the closed form is the undisturbed motion, so the ghost is hidden from then.
  std::optional<double> disturbedAt_;
  std::string sceneHint_;          // the scene's "try this", shown when it opens
  long long hintUntilFrame_ = 360;  // frames: the hint shows for 6 s after a scene opens
  // The panel's advice (advice_job.h): what it asks, the job, and what was applied.
  AdviceRequest adviceRequest_;
  AdviceJob advice_;
  long long adviceFramesWhileRunning_ = 0;  // frames drawn while a survey ran (the loop never waits for it)
  std::string adviceApplied_;               // the options last applied ("" before any)
  bool quit_ = false;
  mutable bool outputFailed_ = false;
  bool frameDue_ = false;
  // Simulated over wall time (real_time.h); paced_: frames follow the 60 Hz
  // clock (interactive, or --realtime), not run flat out by a script.
  RealTimeMeter realTime_;
  bool paced_ = true;
  BuildMode build_;
  bool imguiReady_ = false;
};

}  // namespace demo

#include "app.h"

#include <GL/freeglut.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "backends/imgui_impl_glut.h"
#include "backends/imgui_impl_opengl3.h"
#include "imgui_internal.h"  // ImGui::ErrorCheckEndFrameRecover
#include "screenshot.h"
#include "state_log.h"

namespace demo {

namespace {
constexpr double framesPerSecond = 60.0;  // the frame time the fixed-time mode simulates
constexpr long long rewindFrames = 60;    // how far 'b' goes back: about one second at 1x speed
constexpr int statusFramesShown = 240;
constexpr int hintFramesShown = 360;      // frames a scene's "try this" shows after it opens (as App::hintUntilFrame_)

// What the panes added by v run, relative to pane 1: schemes and steps that
// look different on every scene (one integrator at one dt in every pane would
// draw four identical pictures). A preset with pane 1's own integrator is skipped.
struct ComparePreset {
  const char* integrator;
  double dtFactor;  // × pane 1's dt
};
constexpr ComparePreset comparePresets[] = {
    {"euler", 4.0},             // first order, gains energy: at 4 dt it drifts away or blows up
    {"implicit-euler", 8.0},    // stable at 8 dt, and visibly damped
    {"symplectic-euler", 4.0},  // the seed's scheme at four times the step
    {"midpoint", 4.0},
};

// The "try this" line: the choice's own, else its scene's.
std::string hintFor(const SceneChoice& choice) {
  if (!choice.hint.empty()) return choice.hint;
  const scenes::SceneInfo* info = scenes::findScene(choice.name);
  return info && info->hint ? info->hint : "";
}

// A pixel coordinate from a double that may be huge or NaN (a script's
// window coordinate ≥ 2³¹ or a world point far outside): clamped well inside int.
int toPixel(double v) {
  if (!std::isfinite(v)) return 0;
  return static_cast<int>(std::lround(std::clamp(v, -1e6, 1e6)));
}
}  // namespace

App::App(DemoOptions options)
    : options_(std::move(options)),
      windowWidth_(options_.windowWidth),
      windowHeight_(options_.windowHeight) {
  stepMode_ = options_.lockstep ? StepMode::Lockstep : StepMode::FixedTime;
  showPanel_ = !options_.hidePanel;
  paused_ = options_.startPaused;
  paced_ = options_.paced();
  recording_ = !options_.record.empty();
  if (!options_.script.empty()) script_ = readScript(options_.script);

  SceneChoice first;
  const options::SceneSource& source = options_.source;
  if (options_.sceneKey) {
    for (const SceneKey& k : sceneKeys())
      if (k.key == static_cast<unsigned char>(*options_.sceneKey)) first = k.choice;
  } else if (!source.sceneFile.empty()) {
    first.file = source.sceneFile;
    first.label = source.sceneFile.substr(source.sceneFile.find_last_of('/') + 1);
  } else {
    first.name = first.label = source.scene;
    first.params = source.overrides();
    first.preset = source.preset;
    // The first key's variant that agrees with the given parameters names it.
    for (const SceneKey& k : sceneKeys()) {
      if (k.choice.name != first.name) continue;
      bool agrees = true;
      for (const auto& [key, value] : k.choice.params)
        agrees &= !first.params.count(key) || first.params.at(key) == value;
      if (!agrees) continue;
      first.label = k.choice.label;
      first.params.insert(k.choice.params.begin(), k.choice.params.end());
      break;
    }
  }
  scenes::Scene scene = buildChoice(first);
  const int integrator = integratorIndexByName(options_.integrator.value_or(scene.integrator));
  const double dt = options_.dt.value_or(scene.dt);
  scene_ = first;
  camera_.reset(scene.viewMin, scene.viewMax);
  particles::IntegratorSettings integratorSettings;  // xpbd's from the scene, as its integrator
  integratorSettings.xpbd = scene.integratorSettings.xpbd;
  integratorSettings.dopri5.tolerance = options_.tolerance;
  panes_.push_back(std::make_unique<Simulation>(std::move(scene), integrator, dt));
  panes_.front()->setIntegratorSettings(integratorSettings);
  if (!options_.compare.empty()) {
    // Each pane an integrator, with its own dt or the first pane's.
    setPaneCount(static_cast<int>(options_.compare.size()));
    for (std::size_t k = 0; k < options_.compare.size(); ++k) {
      panes_[k]->setIntegrator(integratorIndexByName(options_.compare[k].integrator));
      panes_[k]->setDt(options_.compare[k].dt.value_or(dt));
    }
    setStatus(compareLine());  // what the panes run now, not the presets they started from
  }
  sceneHint_ = hintFor(scene_);
  exact_ = exactMotion(scene_, *buildChoice(scene_).system);  // a fresh build: the state at t = 0
  mouseSettings_.joint = options_.grab;
  takeWindTearFromScene();
}

App::~App() {
  if (!imguiReady_) return;
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGLUT_Shutdown();
  ImGui::DestroyContext();
}

void App::initGraphics() {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // the layout is the program's, not a file's
  static const char* fontPaths[] = {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"};
  for (const char* path : fontPaths)
    if (std::ifstream(path)) {
      io.Fonts->AddFontFromFileTTF(path, 15.0f);
      break;
    }
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 4.0f;
  style.FrameRounding = 3.0f;
  ImGui_ImplGLUT_Init();
  ImGui_ImplOpenGL3_Init(glslVersion);
  ImGui_ImplGLUT_ReshapeFunc(windowWidth_, windowHeight_);
  imguiReady_ = true;
}

// ---------------------------------------------------------------------------
// One frame

void App::display() {
  if (!frameDue_ && !quit_) {
    guarded([&] { draw(); });
    glutSwapBuffers();
    return;
  }
  frameDue_ = false;
  const auto start = std::chrono::steady_clock::now();
  guarded([&] { pollAdvice(); });
  guarded([&] { playScript(); });
  guarded([&] { advance(); });
  const Simulation& first = *panes_.front();
  realTime_.record(std::chrono::duration<double>(start.time_since_epoch()).count(), first.timeReached(),
                   !paused_ && !first.stopped());
  guarded([&] { draw(); });
  finishFrame();
  if (frameMs_.size() < 1000000) {
    frameMs_.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    double simulation = 0.0;
    for (const auto& pane : panes_) simulation += pane->lastFrame().simulationMs;
    frameSimulationMs_.push_back(simulation);
  }
}

void App::playScript() {
  // Keys a script pressed last frame are released now, after ImGui saw them down.
  for (unsigned char key : scriptKeysDown_) inputKeyUp(key);
  scriptKeysDown_.clear();
  while (nextScriptEvent_ < script_.size() && script_[nextScriptEvent_].frame + scriptHeldFrames_ <= frame_) {
    if (script_[nextScriptEvent_].action == ScriptAction::WaitAdvice && advice_.running()) {
      ++scriptHeldFrames_;  // the script's clock stands still this frame
      return;
    }
    const ScriptEvent& e = script_[nextScriptEvent_++];
    if (e.action == ScriptAction::WaitAdvice) continue;
    if (e.action == ScriptAction::Select || e.action == ScriptAction::Edit) {
      guarded([&] { scriptBuildEvent(e); });
      continue;
    }
    if (e.action == ScriptAction::Key || e.action == ScriptAction::KeyDown) {
      inputKey(e.key);
      if (e.action == ScriptAction::Key) scriptKeysDown_.push_back(e.key);
      continue;
    }
    if (e.action == ScriptAction::KeyUp) {
      inputKeyUp(e.key);
      continue;
    }
    if (e.action == ScriptAction::Resize) {  // GLUT calls reshape() when the window has its new size
      glutReshapeWindow(static_cast<int>(e.x), static_cast<int>(e.y));
      continue;
    }
    Eigen::Vector2d pixel(e.x, e.y);
    if (e.space == ScriptSpace::World) pixel = paneViews().front().toPixel({e.x, e.y});
    const int x = toPixel(pixel.x()), y = toPixel(pixel.y());
    const int button = e.button == ScriptButton::Right    ? GLUT_RIGHT_BUTTON
                       : e.button == ScriptButton::Middle ? GLUT_MIDDLE_BUTTON
                                                          : GLUT_LEFT_BUTTON;
    const bool shift = e.button == ScriptButton::ShiftLeft;
    switch (e.action) {
      case ScriptAction::MouseDown: inputMouse(button, GLUT_DOWN, x, y, shift); break;
      case ScriptAction::MouseMove:
        if (tool_ == MouseTool::None && !panning_) inputPassiveMotion(x, y);
        else inputMotion(x, y);
        break;
      case ScriptAction::MouseUp: inputMouse(button, GLUT_UP, x, y, shift); break;
      case ScriptAction::Wheel: inputWheel(e.clicks, x, y); break;
      default: break;
    }
  }
}

void App::advance() {
  if (build_.active()) return;  // the scene being built stays at t = 0
  if (stepRequested_) {
    for (auto& pane : panes_) pane->stepOnce();
  } else if (!paused_) {
    std::vector<Simulation*> panes;
    for (auto& pane : panes_) panes.push_back(pane.get());
    lastBudget_ = stepPanesWithinBudget(panes, speed_ / framesPerSecond, stepMode_, options_.stepBudgetMs);
    budgetTally_.add(lastBudget_);
  }
  for (auto& pane : panes_)
    if (const std::string notice = pane->takeNotice(); !notice.empty()) setStatus(notice);
  stepRequested_ = false;
  // A single simulation that diverges pauses the demo; in compare mode the
  // diverged pane stops alone so the others can be watched on.
  if (panes_.size() == 1 && panes_.front()->divergedAt()) paused_ = true;
}

void App::drawPanes(const std::vector<ViewTransform>& views) {
  paneDrawings_.resize(panes_.size());
  for (std::size_t k = 0; k < panes_.size(); ++k) {
    GhostFrame ghost;
    // Running with a dt longer than a frame, the drawing is between steps
    // (Simulation::drawnFraction), and the ghost at the time drawn.
    DrawOptions options = drawOptions_;
    options.frameTime = paused_ || stepMode_ == StepMode::Lockstep ? 0.0 : speed_ / framesPerSecond;
    const Simulation& pane = *panes_[k];
    const double drawnTime = pane.system().time() - (1.0 - pane.drawnFraction(options.frameTime)) * pane.dt();
    const bool ghostShown = exact_ && !disturbedAt_;
    if (ghostShown) ghost = exact_(drawnTime);
    renderer_.drawPane(pane, views[k], windowHeight_, options, ghostShown ? &ghost : nullptr);
    paneDrawings_[k] = renderer_.drawing();
  }
}

void App::draw() {
  const auto start = std::chrono::steady_clock::now();
  renderer_.clearWindow(windowWidth_, windowHeight_, palette::paneBorder);
  const std::vector<ViewTransform> views = paneViews();
  drawPanes(views);
  if (build_.active()) drawBuildOverlay(views.front());
  // The drawing is timed on one frame in drawTimingPeriod, which waits for
  // the GL to finish so that the time includes its work, not just its
  // submission. The other frames let the rasteriser work on while the next
  // part is built (a software rasteriser's frame is ~4 ms shorter for it).
  const bool timed = frame_ % drawTimingPeriod == 0;
  if (timed) glFinish();
  const auto sceneDone = std::chrono::steady_clock::now();
  if (timed) sceneDrawMs_ = std::chrono::duration<double, std::milli>(sceneDone - start).count();
  glViewport(0, 0, windowWidth_, windowHeight_);

  if (!imguiReady_) return;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGLUT_NewFrame();  // also ImGui::NewFrame() in 1.86
  overlays_.clear();
  widgets_.clear();
  backdrops_.clear();
  // Between NewFrame and Render nothing may leave the frame open: an error
  // thrown by a panel closes the windows it left open and ends the frame
  // before it reaches the top bar (an open frame aborts the next NewFrame,
  // ImGui's "Forgot to call Render()").
  try {
    drawTopBar();
    drawBottomBar();
    if (panes_.size() > 1) drawPaneHeaders();
    drawOutOfViewIndicators();
    if (showHelp_) drawHelp();
    if (showPanel_) drawPanel();
  } catch (...) {
    ImGui::ErrorCheckEndFrameRecover(nullptr);
    ImGui::EndFrame();
    throw;
  }
  closePopups_ = false;
  ImGui::Render();
  for (const Backdrop& b : backdrops_) renderer_.clearRect(b.rect, windowHeight_, b.colour);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (!timed) return;
  glFinish();
  overlayDrawMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - sceneDone).count();
  if (frame_ > 0 && overlayDrawSamples_.size() < 100000) {
    sceneDrawSamples_.push_back(sceneDrawMs_);
    overlayDrawSamples_.push_back(overlayDrawMs_);
  }
}

// A numbered PNG name in a directory: DIR/stem-000042.png.
static std::string numberedImage(const std::string& dir, const char* stem, long long number) {
  char name[64];
  std::snprintf(name, sizeof name, "%s-%06lld.png", stem, number);
  return (std::filesystem::path(dir.empty() ? "." : dir) / name).string();
}

// A write that failed while the demo runs (a frame of --record, a k
// screenshot): one line on stderr as it happens, as particle-lab reports a
// failed output, the top bar too, and the exit code at the end says so.
void App::reportFailedWrite(const std::string& message) {
  reportBadUsage(message);
  setError(message);
  outputFailed_ = true;
}

void App::writeFrameImages() {
  if (recording_) {
    const std::string error = writeScreenshot(numberedImage(recordDirectory(), "frame", frame_), windowWidth_,
                                              windowHeight_, "--record");
    if (!error.empty()) {
      reportFailedWrite("recording stopped: " + error);
      recording_ = false;
    }
  }
  if (screenshotRequested_) {
    screenshotRequested_ = false;
    const std::string path = numberedImage(options_.record, "screenshot", frame_);
    const std::string error = writeScreenshot(path, windowWidth_, windowHeight_, "the k key's screenshot");
    if (error.empty()) setStatus("screenshot: " + path);
    else reportFailedWrite(error);
  }
}

void App::finishFrame() {
  if (statusFrames_ > 0) --statusFrames_;
  ++frame_;
  writeFrameImages();
  const bool last = quit_ || (options_.frames && frame_ >= *options_.frames);
  if (last && !options_.screenshot.empty()) {
    const std::string error = writeScreenshot(options_.screenshot, windowWidth_, windowHeight_, "--screenshot");
    if (!error.empty()) {
      reportBadUsage(error);
      outputFailed_ = true;
    }
  }
  glutSwapBuffers();
  if (last) {
    quit_ = true;
    glutLeaveMainLoop();
  }
}

bool App::writeStateLog() const {
  if (options_.logState.empty()) return true;
  std::vector<PaneState> states;
  const std::vector<ViewTransform> views = paneViews();
  for (std::size_t k = 0; k < panes_.size(); ++k)
    states.push_back({scene_.label, panes_[k].get(), views[k], k < paneDrawings_.size() ? paneDrawings_[k] : Renderer::PaneDrawing{}});
  StateExtras extras;
  extras.overlays = overlays_;
  extras.widgets = widgets_;
  extras.advice.state = adviceStateName(advice_.state());
  extras.advice.progress = advice_.progress();
  if (advice_.state() == AdviceState::Done && advice_.advice().best >= 0) {
    const lab::Candidate& pick = advice_.advice().picks[advice_.advice().best].candidate;
    extras.advice.integrator = pick.integrator;
    extras.advice.dt = pick.dt;
    extras.advice.tolerance = pick.tolerance;
  }
  extras.advice.framesWhileRunning = adviceFramesWhileRunning_;
  extras.build = {build_.active(), build_.tool().name, build_.selection ? build_.selection->name() : "scene",
                  build_.file, build_.history.empty() ? 0 : build_.history.position() + 1, build_.history.size(),
                  build_.pending().size(), build_.grid};
  extras.advice.applied = adviceApplied_;
  extras.sceneDrawMs = sceneDrawMs_;
  extras.overlayDrawMs = overlayDrawMs_;
  extras.sceneDrawSamples = sceneDrawSamples_;
  extras.overlayDrawSamples = overlayDrawSamples_;
  extras.panelShown = showPanel_;
  extras.frameMs = frameMs_;
  extras.frameSimulationMs = frameSimulationMs_;
  extras.lastBudget = lastBudget_;
  extras.budgetTally = budgetTally_;
  extras.realTime = {realTime_.known() ? realTime_.ratio() : 0.0, realTime_.totalSimSeconds(),
                     realTime_.totalWallSeconds(), paced_};
  const std::string error = writeStateFile(options_.logState, states, extras, frame_, paused_);
  if (error.empty()) return true;
  reportBadUsage(error);
  outputFailed_ = true;
  return false;
}

// ---------------------------------------------------------------------------
// Actions

void App::loadScene(const SceneChoice& choice, bool keepIntegrators) {
  std::vector<std::unique_ptr<Simulation>> fresh;
  Eigen::Vector2d viewMin, viewMax;
  for (std::size_t k = 0; k < panes_.size(); ++k) {
    scenes::Scene scene = buildChoice(choice);  // throws before anything changes
    // The first pane takes the scene's integrator and xpbd's settings with it;
    // dopri5's tolerance stays the user's (--tolerance, the panel).
    const bool fromScene = !keepIntegrators && k == 0;
    const int integrator = fromScene ? integratorIndexByName(scene.integrator) : panes_[k]->integratorIndex();
    particles::IntegratorSettings settings = panes_[k]->integratorSettings();
    if (fromScene) settings.xpbd = scene.integratorSettings.xpbd;
    viewMin = scene.viewMin;
    viewMax = scene.viewMax;
    const double dt = scene.dt;
    fresh.push_back(std::make_unique<Simulation>(std::move(scene), integrator, dt));
    fresh.back()->setIntegratorSettings(settings);
  }
  replacePanes(std::move(fresh));
  scene_ = choice;
  takeWindTearFromScene();
  camera_.reset(viewMin, viewMax);
  paused_ = options_.startPaused && frame_ == 0;
  sceneHint_ = hintFor(choice);
  exact_ = exactMotion(choice, *buildChoice(choice).system);
  disturbedAt_.reset();
  setStatus("scene: " + choice.label);
  statusFrames_ = 0;  // the top bar shows the scene's summary and hint instead
  hintUntilFrame_ = frame_ + hintFramesShown;
  if (build_.active()) startBuildFrom(documentOf(panes_.front()->scene()), "start from " + choice.label);
}

// --- advice (advice_job.h; drawn by advice_panel.cpp) -----------------------

void App::startAdvice() {
  advice_.start(scene_, adviceRequest_);
  adviceFramesWhileRunning_ = 0;
  setStatus("advice: surveying a copy of " + scene_.label + " over " + lab::general(adviceRequest_.horizon) + " s");
}

void App::pollAdvice() {
  if (advice_.running()) ++adviceFramesWhileRunning_;
  if (!advice_.poll()) return;
  switch (advice_.state()) {
    case AdviceState::Done:
      if (advice_.advice().best >= 0)
        setStatus("advice: " + lab::pickArguments(advice_.advice().picks[advice_.advice().best].candidate) +
                  " (Apply sets it)");
      else
        setStatus("advice: no integrator meets E = " + lab::general(advice_.request().error) + " over " +
                  lab::general(advice_.request().horizon) + " s within its safe range");
      break;
    case AdviceState::Cancelled: setStatus("advice cancelled"); break;
    case AdviceState::Failed: setError("advice failed: " + advice_.message()); break;
    default: break;
  }
}

bool App::adviceIsForThisScene() const {
  const SceneChoice& a = advice_.scene();
  return a.name == scene_.name && a.file == scene_.file && a.params == scene_.params && a.preset == scene_.preset &&
         a.document == scene_.document;
}

// The cheapest pick's integrator, dt and tolerance, on the first pane (the
// one the advice names; compare panes keep theirs). The state runs on.
void App::applyAdvice() {
  if (advice_.state() != AdviceState::Done || advice_.advice().best < 0)
    throw std::invalid_argument("advice: nothing to apply");
  if (!adviceIsForThisScene()) throw std::invalid_argument("advice: computed for another scene; advise again");
  const lab::Candidate& pick = advice_.advice().picks[advice_.advice().best].candidate;
  Simulation& pane = *panes_.front();
  particles::IntegratorSettings settings = pane.integratorSettings();
  if (pick.tolerance > 0.0) settings.dopri5.tolerance = pick.tolerance;
  pane.setIntegratorSettings(settings);
  pane.setIntegrator(integratorIndexByName(pick.integrator));
  pane.setDt(pick.dt);
  adviceApplied_ = lab::pickArguments(pick);
  setStatus("applied " + adviceApplied_ + (panes_.size() > 1 ? " to pane 1" : ""));
}

void App::resetScene() {
  std::vector<std::unique_ptr<Simulation>> fresh;
  for (const auto& pane : panes_) {
    fresh.push_back(std::make_unique<Simulation>(buildChoice(scene_), pane->integratorIndex(), pane->dt()));
    fresh.back()->setIntegratorSettings(pane->integratorSettings());
  }
  replacePanes(std::move(fresh));
  applyWindTear();  // the wind and tearing the user set outlast a reset
  sceneView();
  paused_ = false;
  disturbedAt_.reset();
  setStatus("reset");
}

// The mouse tool names a particle and a pane of the panes it was pressed on:
// panes of another scene (a scene key, N or z in build mode) drop it with
// them, or a drag after the change would place a particle past the end.
void App::replacePanes(std::vector<std::unique_ptr<Simulation>> panes) {
  panes_ = std::move(panes);
  tool_ = MouseTool::None;
  toolParticle_ = toolPane_ = -1;
  panning_ = false;
}

void App::setPaneCount(int count) {
  const Simulation& first = *panes_.front();
  const std::string firstName = first.integratorName();
  std::vector<ComparePreset> presets;
  for (const ComparePreset& p : comparePresets)
    if (firstName != p.integrator) presets.push_back(p);
  // Every new pane is built before any changes, so a scene file that became
  // invalid since it was loaded leaves the panes as they were.
  std::vector<std::unique_ptr<Simulation>> added;
  for (int k = 1; k < count; ++k) {
    const ComparePreset& preset = presets[(k - 1) % presets.size()];
    auto pane = std::make_unique<Simulation>(buildChoice(scene_), integratorIndexByName(preset.integrator),
                                             first.dt() * preset.dtFactor);
    pane->setIntegratorSettings(first.integratorSettings());
    pane->copyStateFrom(first);  // the same state, clock and history: the panes start together
    added.push_back(std::move(pane));
  }
  panes_.resize(1);
  panes_.front()->release();
  for (auto& pane : added) panes_.push_back(std::move(pane));
  tool_ = MouseTool::None;
  if (count > 1) setStatus(compareLine());
}

// The panes as they run, in pane order: "compare: 1 euler dt 0.005, 2 ...".
std::string App::compareLine() const {
  std::string names;
  for (std::size_t k = 0; k < panes_.size(); ++k) {
    char entry[96];
    std::snprintf(entry, sizeof entry, "%s%zu %s dt %g", k ? ", " : "", k + 1, panes_[k]->integratorName(), panes_[k]->dt());
    names += entry;
  }
  return "compare: " + names;
}

// "integrator: rk4 (order 4): loses a little energy, ...": the scheme's
// order, stability and cost in one line.
std::string App::integratorLine(int index) {
  const particles::IntegratorInfo& info = particles::integratorTable().at(static_cast<std::size_t>(index));
  return std::string("integrator: ") + info.name + " (order " + std::to_string(info.order) + "): " + info.behaviour;
}

void App::cycleIntegrators() {
  const int tableSize = static_cast<int>(particles::integratorTable().size());
  for (auto& pane : panes_) pane->setIntegrator((pane->integratorIndex() + 1) % tableSize);
  setStatus(integratorLine(panes_.front()->integratorIndex()));
}

void App::scaleDt(double factor) {
  // Checked for every pane before any changes: halving to 0 (from 5e-324) or
  // doubling to infinity is refused with the reason.
  for (const auto& pane : panes_) {
    const double dt = pane->dt() * factor;
    if (!(dt >= std::numeric_limits<double>::min()) || !std::isfinite(dt)) {
      char text[160];
      std::snprintf(text, sizeof text, "dt = %g cannot be %s further (it would be %g)", pane->dt(),
                    factor > 1.0 ? "doubled" : "halved", dt);
      setError(text);
      return;
    }
  }
  for (auto& pane : panes_) pane->setDt(pane->dt() * factor);
  char text[64];
  std::snprintf(text, sizeof text, "dt = %g", panes_.front()->dt());
  setStatus(text);
}

void App::rewind() {
  // One frame for every pane, so compare panes come back to one time: about
  // a second before the pane that stopped first (or before now), the newest
  // frame every pane has recorded.
  long long reached = panes_.front()->frames();
  for (const auto& pane : panes_) reached = std::min(reached, pane->frames());
  const long long target = std::max(0LL, reached - rewindFrames);
  const auto& entries = panes_.front()->history().entries();
  std::optional<long long> frame;
  for (auto it = entries.rbegin(); it != entries.rend() && !frame; ++it) {
    if (it->frame > target) continue;
    bool everywhere = true;
    for (const auto& pane : panes_) everywhere &= pane->history().has(it->frame);
    if (everywhere) frame = it->frame;
  }
  if (!frame) {
    setError("nothing recorded to rewind to");
    return;
  }
  for (auto& pane : panes_) pane->rewindTo(*frame);
  // Back before the first disturbance, the motion is the closed form's again.
  if (disturbedAt_ && panes_.front()->system().time() < *disturbedAt_) disturbedAt_.reset();
  paused_ = true;
  char text[128];
  std::snprintf(text, sizeof text, "rewound to t = %.2f s (paused: space runs, - halves dt)",
                panes_.front()->system().time());
  setStatus(text);
}

void App::setStatus(const std::string& text) {
  status_ = text;
  statusIsError_ = false;
  statusFrames_ = statusFramesShown;
}

void App::setError(const std::string& text) {
  status_ = text;
  statusIsError_ = true;
  statusFrames_ = 2 * statusFramesShown;
}

// ---------------------------------------------------------------------------
// Layout

Layout App::layout() const {
  LayoutMetrics metrics;
  if (!drawOptions_.forces) metrics.legendLines = 0;
  return computeLayout(windowWidth_, windowHeight_, showPanel_, static_cast<int>(panes_.size()), metrics);
}

std::vector<ViewTransform> App::paneViews() const {
  std::vector<ViewTransform> views;
  const Layout l = layout();
  for (std::size_t k = 0; k < panes_.size(); ++k) views.push_back(fitView(l.worlds[k], camera_.min(), camera_.max()));
  return views;
}

int App::paneAt(int x, int y) const {
  const std::vector<ViewTransform> views = paneViews();
  for (std::size_t k = 0; k < views.size(); ++k)
    if (views[k].pane.contains(x, y)) return static_cast<int>(k);
  return -1;
}

void App::reshape(int width, int height) {
  windowWidth_ = std::max(width, 1);
  windowHeight_ = std::max(height, 1);
  if (imguiReady_) ImGui_ImplGLUT_ReshapeFunc(windowWidth_, windowHeight_);
}

}  // namespace demo

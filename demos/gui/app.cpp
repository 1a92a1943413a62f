#include "app.h"

#include <GL/freeglut.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "backends/imgui_impl_glut.h"
#include "backends/imgui_impl_opengl2.h"
#include "screenshot.h"
#include "state_log.h"

namespace demo {

namespace {
constexpr double framesPerSecond = 60.0;  // the frame time the fixed-time mode simulates
constexpr int panelWidth = 340;           // pixels at the right edge, when shown
constexpr double rewindSeconds = 1.0;     // how far 'b' goes back
constexpr int statusFramesShown = 180;

int integratorIndexByName(const std::string& name) {
  const auto& table = particles::integratorTable();
  for (std::size_t k = 0; k < table.size(); ++k)
    if (name == table[k].name) return static_cast<int>(k);
  particles::makeIntegrator(name);  // throws, listing the valid names
  return 0;
}
}  // namespace

App::App(DemoOptions options)
    : options_(std::move(options)),
      windowWidth_(options_.windowWidth),
      windowHeight_(options_.windowHeight) {
  stepMode_ = options_.lockstep ? StepMode::Lockstep : StepMode::FixedTime;
  showPanel_ = !options_.hidePanel;
  paused_ = options_.startPaused;
  if (!options_.script.empty()) script_ = readScript(options_.script);

  SceneChoice first;
  if (!options_.sceneFile.empty()) {
    first.file = options_.sceneFile;
    first.label = options_.sceneFile.substr(options_.sceneFile.find_last_of('/') + 1);
  } else {
    first.name = first.label = options_.scene;
    first.params = options_.params;
    first.preset = options_.preset;
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
  panes_.push_back(std::make_unique<Simulation>(std::move(scene), integrator, dt));
  particles::IntegratorSettings integratorSettings;
  integratorSettings.tolerance = options_.tolerance;
  panes_.front()->setIntegratorSettings(integratorSettings);
  if (!options_.compare.empty()) {
    // Each entry is an integrator, optionally with its own dt: "rk4" or "rk4:0.02".
    std::vector<std::pair<int, double>> settings;
    for (const std::string& entry : options_.compare) {
      const auto colon = entry.find(':');
      double paneDt = dt;
      if (colon != std::string::npos) {
        char* end = nullptr;
        paneDt = std::strtod(entry.c_str() + colon + 1, &end);
        if (end == entry.c_str() + colon + 1 || *end != '\0' || !(paneDt > 0.0) || !std::isfinite(paneDt))
          throw std::invalid_argument("--compare: dt in '" + entry + "' must be a finite number > 0");
      }
      settings.emplace_back(integratorIndexByName(entry.substr(0, colon)), paneDt);
    }
    setPaneCount(static_cast<int>(settings.size()));
    for (std::size_t k = 0; k < settings.size(); ++k) {
      panes_[k]->setIntegrator(settings[k].first);
      panes_[k]->setDt(settings[k].second);
    }
  }
}

App::~App() {
  if (!imguiReady_) return;
  ImGui_ImplOpenGL2_Shutdown();
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
  ImGui_ImplOpenGL2_Init();
  ImGui_ImplGLUT_ReshapeFunc(windowWidth_, windowHeight_);
  imguiReady_ = true;
}

// ---------------------------------------------------------------------------
// One frame

void App::display() {
  if (!frameDue_ && !quit_) {
    draw();
    glutSwapBuffers();
    return;
  }
  frameDue_ = false;
  playScript();
  advance();
  draw();
  finishFrame();
}

void App::playScript() {
  while (nextScriptEvent_ < script_.size() && script_[nextScriptEvent_].frame <= frame_) {
    const ScriptEvent& e = script_[nextScriptEvent_++];
    if (e.action == ScriptAction::Key) {
      keyboard(e.key);
      continue;
    }
    if (e.action == ScriptAction::Resize) {  // GLUT calls reshape() when the window has its new size
      glutReshapeWindow(static_cast<int>(e.x), static_cast<int>(e.y));
      continue;
    }
    Eigen::Vector2d pixel(e.x, e.y);
    if (e.space == ScriptSpace::World) pixel = paneViews().front().toPixel({e.x, e.y});
    const int x = static_cast<int>(std::lround(pixel.x())), y = static_cast<int>(std::lround(pixel.y()));
    const int button = e.button == ScriptButton::Right ? GLUT_RIGHT_BUTTON : GLUT_LEFT_BUTTON;
    const bool shift = e.button == ScriptButton::ShiftLeft;
    switch (e.action) {
      case ScriptAction::MouseDown: mouse(button, GLUT_DOWN, x, y, shift); break;
      case ScriptAction::MouseMove: motion(x, y); break;
      case ScriptAction::MouseUp: mouse(button, GLUT_UP, x, y, shift); break;
      case ScriptAction::Key: case ScriptAction::Resize: break;
    }
  }
}

void App::advance() {
  const bool run = !paused_ || stepRequested_;
  for (auto& pane : panes_) {
    if (stepRequested_) pane->stepOnce();
    else if (run) pane->advanceFrame(speed_ / framesPerSecond, stepMode_);
  }
  stepRequested_ = false;
  // A single simulation that diverges pauses the demo; in compare mode the
  // diverged pane stops alone so the others can be watched on.
  if (panes_.size() == 1 && panes_.front()->divergedAt()) paused_ = true;
}

void App::draw() {
  const auto start = std::chrono::steady_clock::now();
  renderer_.clearWindow(windowWidth_, windowHeight_, palette::paneBorder);
  const std::vector<ViewTransform> views = paneViews();
  for (std::size_t k = 0; k < panes_.size(); ++k)
    renderer_.drawPane(*panes_[k], views[k], windowHeight_, drawOptions_);
  glFinish();  // so that the time includes the GL work, not just its submission
  drawMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  glViewport(0, 0, windowWidth_, windowHeight_);

  if (!imguiReady_) return;
  ImGui_ImplOpenGL2_NewFrame();
  ImGui_ImplGLUT_NewFrame();  // also ImGui::NewFrame() in 1.86
  overlays_.clear();
  drawHud();
  drawDivergenceMessages();
  if (drawOptions_.forces) drawForceLegend();
  if (showHelp_) drawHelp();
  if (showPanel_) drawPanel();
  ImGui::Render();
  ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
}

void App::finishFrame() {
  if (statusFrames_ > 0) --statusFrames_;
  ++frame_;
  const bool last = quit_ || (options_.frames && frame_ >= *options_.frames);
  if (last && !options_.screenshot.empty()) {
    const std::string error = writeScreenshot(options_.screenshot, windowWidth_, windowHeight_);
    if (!error.empty()) std::fprintf(stderr, "particle-demo: %s\n", error.c_str());
  }
  glutSwapBuffers();
  if (last) {
    quit_ = true;
    glutLeaveMainLoop();
  }
}

void App::writeStateLog() const {
  if (options_.logState.empty()) return;
  std::vector<PaneState> states;
  const std::vector<ViewTransform> views = paneViews();
  for (std::size_t k = 0; k < panes_.size(); ++k) states.push_back({scene_.label, panes_[k].get(), views[k]});
  const std::string error = writeStateFile(options_.logState, states, overlays_, frame_, paused_);
  if (!error.empty()) std::fprintf(stderr, "particle-demo: %s\n", error.c_str());
}

// ---------------------------------------------------------------------------
// Actions

void App::loadScene(const SceneChoice& choice, bool keepIntegrators) {
  std::vector<std::unique_ptr<Simulation>> fresh;
  for (std::size_t k = 0; k < panes_.size(); ++k) {
    scenes::Scene scene = buildChoice(choice);  // throws before anything changes
    const int integrator = keepIntegrators || k > 0 ? panes_[k]->integratorIndex()
                                                    : integratorIndexByName(scene.integrator);
    const double dt = scene.dt;
    fresh.push_back(std::make_unique<Simulation>(std::move(scene), integrator, dt));
    fresh.back()->setIntegratorSettings(panes_[k]->integratorSettings());
  }
  panes_ = std::move(fresh);
  scene_ = choice;
  tool_ = MouseTool::None;
  paused_ = options_.startPaused && frame_ == 0;
}

void App::resetScene() {
  std::vector<std::unique_ptr<Simulation>> fresh;
  for (const auto& pane : panes_)
  {
    fresh.push_back(std::make_unique<Simulation>(buildChoice(scene_), pane->integratorIndex(), pane->dt()));
    fresh.back()->setIntegratorSettings(pane->integratorSettings());
  }
  panes_ = std::move(fresh);
  tool_ = MouseTool::None;
  paused_ = false;
  setStatus("reset");
}

void App::setPaneCount(int count) {
  const int tableSize = static_cast<int>(particles::integratorTable().size());
  const Simulation& first = *panes_.front();
  std::vector<std::unique_ptr<Simulation>> fresh;
  fresh.push_back(std::move(panes_.front()));
  for (int k = 1; k < count; ++k) {
    // Each new pane starts from the first pane's state with the next integrator.
    auto pane = std::make_unique<Simulation>(buildChoice(scene_), (first.integratorIndex() + k) % tableSize,
                                             first.dt());
    pane->copyStateFrom(first);
    pane->setIntegratorSettings(first.integratorSettings());
    fresh.push_back(std::move(pane));
  }
  fresh.front()->release();
  panes_ = std::move(fresh);
  tool_ = MouseTool::None;
}

void App::cycleIntegrators() {
  const int tableSize = static_cast<int>(particles::integratorTable().size());
  for (auto& pane : panes_) pane->setIntegrator((pane->integratorIndex() + 1) % tableSize);
  setStatus(std::string("integrator: ") + panes_.front()->integratorName());
}

void App::scaleDt(double factor) {
  for (auto& pane : panes_) pane->setDt(pane->dt() * factor);
  char text[64];
  std::snprintf(text, sizeof text, "dt = %g", panes_.front()->dt());
  setStatus(text);
}

void App::rewind() {
  // One target time for every pane, so compare panes stay side by side in
  // time: a second before the earliest divergence (or before now).
  double target = panes_.front()->timeReached();
  for (const auto& pane : panes_) target = std::min(target, pane->timeReached());
  target -= rewindSeconds;
  std::optional<double> to;
  for (auto& pane : panes_) to = pane->rewindTo(target);
  if (!to) return;
  paused_ = true;
  char text[128];
  std::snprintf(text, sizeof text, "rewound to t = %.2f s (paused: space runs, - halves dt)", *to);
  setStatus(text);
}

void App::setStatus(const std::string& text) {
  status_ = text;
  statusFrames_ = statusFramesShown;
}

// ---------------------------------------------------------------------------
// Layout

PixelRect App::worldArea() const {
  const int panel = showPanel_ ? std::min(panelWidth, windowWidth_ / 2) : 0;
  return {0, 0, windowWidth_ - panel, windowHeight_};
}

std::vector<ViewTransform> App::paneViews() const {
  std::vector<ViewTransform> views;
  const std::vector<PixelRect> rects = splitPanes(worldArea(), static_cast<int>(panes_.size()));
  for (std::size_t k = 0; k < panes_.size(); ++k)
    views.push_back(fitView(rects[k], panes_[k]->scene().viewMin, panes_[k]->scene().viewMax));
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

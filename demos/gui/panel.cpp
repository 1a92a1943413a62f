// The ImGui control panel at the right edge of the window (key p).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "app.h"
#include "panel_rows.h"
#include "particles/constraint_solver.h"
#include "particles/threads.h"
#include "scenes/wind_and_tearing.h"

namespace demo {

namespace {
using scenes::findScene;

// The constraint solve's choices as the panel shows them (scene files use
// particles/solver_names.h).
template <class Value>
struct Labelled {
  Value value;
  const char* label;
};
const std::vector<Labelled<particles::SolveMethod>> kSolveMethodLabels = {
    {particles::SolveMethod::Direct, "direct (LDLT)"},
    {particles::SolveMethod::ConjugateGradient, "conjugate gradient"},
};
const std::vector<Labelled<particles::Preconditioner>> kPreconditionerLabels = {
    {particles::Preconditioner::None, "none"},
    {particles::Preconditioner::Jacobi, "Jacobi"},
    {particles::Preconditioner::IncompleteCholesky, "incomplete Cholesky"},
};

// A combo over one of the label tables above,
// showing each choice's label; true when the choice changed.
template <class Value>
bool choose(const char* label, const std::vector<Labelled<Value>>& table, Value& value) {
  const char* current = "?";
  for (const auto& e : table)
    if (e.value == value) current = e.label;
  bool changed = false;
  if (ImGui::BeginCombo(label, current)) {
    for (const auto& e : table)
      if (ImGui::Selectable(e.label, e.value == value)) {
        changed = e.value != value;
        value = e.value;
      }
    ImGui::EndCombo();
  }
  return changed;
}

// A trace against frames (newest at the right), labelled with its quantity and
// unit; the overlay gives the newest value and the y axis's range, which is
// the trace's own minimum to maximum.
// An ImGui colour as it blends over an opaque one, in ImGui's 8-bit
// channels: c a + under (1 − a).
Rgb over(const ImVec4& c, Rgb under) {
  const ImU32 packed = ImGui::ColorConvertFloat4ToU32(c);
  const int a = static_cast<int>(packed >> IM_COL32_A_SHIFT & 0xFF);
  auto channel = [&](int shift, std::uint8_t below) {
    const int top = static_cast<int>(packed >> shift & 0xFF);
    return static_cast<std::uint8_t>((top * a + below * (255 - a) + 127) / 255);
  };
  return {channel(IM_COL32_R_SHIFT, under.r), channel(IM_COL32_G_SHIFT, under.g), channel(IM_COL32_B_SHIFT, under.b)};
}

void plot(const char* label, const char* unit, const std::vector<float>& values, float height) {
  if (values.empty()) return;
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  char overlay[96];
  std::snprintf(overlay, sizeof overlay, "%.4g %s\ny %.3g to %.3g", values.back(), unit, *lo, *hi);
  ImGui::PlotLines(label, values.data(), static_cast<int>(values.size()), 0, overlay, *lo,
                   *hi > *lo ? *hi : *lo + 1e-12f, ImVec2(0.0f, height));
}
}  // namespace

void App::recordWidget(const char* name) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  widgets_.push_back({name, {static_cast<int>(a.x), static_cast<int>(a.y), static_cast<int>(b.x - a.x), static_cast<int>(b.y - a.y)}, ""});
}

void App::drawPanel() {
  const PixelRect area = layout().panel;
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(area.x), 0.0f));
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(area.width), static_cast<float>(area.height)));
  // The panel's background is a backdrop (app.h): the colour ImGui's WindowBg
  // has over the window's, filled by a clear; ImGui draws none, and the
  // panel's corners are square, as the rectangle filled.
  backdrops_.push_back({area, over(ImGui::GetStyleColorVec4(ImGuiCol_WindowBg), palette::paneBorder)});
  ImGui::PushStyleColor(ImGuiCol_WindowBg, IM_COL32(0, 0, 0, 0));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
  // The scroll bar is always there, so that the rows that wrap (panel_rows.h)
  // wrap alike whether the panel's content overflows or not, and a control
  // keeps its place when a section opens.
  ImGui::Begin("Control panel", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_AlwaysVerticalScrollbar);
  ImGui::PopStyleVar();
  ImGui::PopStyleColor();
  ImGui::PushItemWidth(-110.0f);

  drawSceneSection();
  ImGui::BeginDisabled(build_.active());  // in build mode the scene's own fields set these
  drawWindTearSection();  // wind_panel.cpp: what blows and tears now, beside the scene it acts on
  ImGui::EndDisabled();
  drawBuildSection();
  ImGui::BeginDisabled(build_.active());
  drawIntegrationSection();
  drawAdvicePanel();  // the cheapest integrator and dt within an error over a horizon
  drawPlotsSection();
  drawSolverSection();
  ImGui::EndDisabled();
  drawDisplaySection();

  ImGui::PopItemWidth();
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  overlays_.push_back({"panel", {static_cast<int>(at.x), static_cast<int>(at.y), static_cast<int>(size.x), static_cast<int>(size.y)}, ""});
  ImGui::End();
}

// --- scene --------------------------------------------------------------------
void App::drawSceneSection() {
  if (!ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) return;
  drawSceneCombo();
  drawPresetCombo();
  drawSceneParams();
  drawRunButtons();
}

// Every scene: the number keys' with their key, then the gallery's, each
// with its summary as a tooltip.
void App::drawSceneCombo() {
  const std::vector<SceneChoice> choices = sceneChoices();
  const std::vector<SceneKey> keys = sceneKeys();
  const bool sceneListOpen = ImGui::BeginCombo("scene", scene_.label.c_str(), ImGuiComboFlags_HeightLargest);
  recordWidget("scene");
  if (!sceneListOpen) return;
  if (closePopups_) ImGui::CloseCurrentPopup();
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  widgets_.push_back({"scene-list", {static_cast<int>(at.x), static_cast<int>(at.y), static_cast<int>(size.x), static_cast<int>(size.y)}, ""});
  for (std::size_t k = 0; k < choices.size(); ++k) {
    const SceneChoice& choice = choices[k];
    if (k == keys.size()) {
      ImGui::Separator();
      ImGui::TextDisabled("gallery: things meeting each other");
    }
    const std::string key = k < keys.size() ? std::string(1, static_cast<char>(keys[k].key)) : " ";
    if (ImGui::Selectable((key + "  " + choice.label).c_str(), choice.label == scene_.label))
      guarded([&] { chooseScene(choice); });
    if (const scenes::SceneInfo* info = findScene(choice.name); info && ImGui::IsItemHovered())
      ImGui::SetTooltip("%s\n%s", info->summary, info->hint);
  }
  ImGui::EndCombo();
}

// The preset fills every parameter of a built-in scene; choosing one rebuilds it.
void App::drawPresetCombo() {
  if (scene_.name.empty() || !ImGui::BeginCombo("preset", scene_.preset.c_str())) return;
  for (const scenes::PresetInfo& preset : scenes::presetTable()) {
    if (ImGui::Selectable(preset.name, scene_.preset == preset.name) && scene_.preset != preset.name) {
      SceneChoice changed = scene_;
      changed.preset = preset.name;
      try {
        const bool keepIntegrators = true;
        loadScene(changed, keepIntegrators);
        setStatus(std::string("preset: ") + preset.name);
      } catch (const std::exception& e) {
        setStatus(e.what());
      }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", preset.summary);
  }
  ImGui::EndCombo();
}

// The parameters the Wind and tearing section sets on the running scene
// (scenes::WindTearParams): listed there, with their live values, not here.
static bool setLive(const std::string& name) {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    scenes::WindTearParams().visitWindTear([&](const char* n, auto&, const char*) { all.push_back(n); });
    return all;
  }();
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Parameters: changing one rebuilds the scene (grid size, chain length, ...).
void App::drawSceneParams() {
  const scenes::SceneInfo* info = findScene(scene_.name);
  if (!info) return;
  for (const scenes::ParamSpec& spec : info->params) {
    if (setLive(spec.name)) continue;
    auto it = scene_.params.find(spec.name);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%s", it != scene_.params.end() ? it->second.c_str() : spec.value(scene_.preset).c_str());
    if (ImGui::InputText(spec.name.c_str(), buffer, sizeof buffer, ImGuiInputTextFlags_EnterReturnsTrue)) {
      SceneChoice changed = scene_;
      changed.params[spec.name] = buffer;
      try {
        const bool keepIntegrators = true;
        loadScene(changed, keepIntegrators);
        setStatus("rebuilt with " + spec.name + " = " + buffer);
      } catch (const std::exception& e) {
        setStatus(e.what());
      }
    }
    if (ImGui::IsItemHovered() && !spec.help.empty())
      ImGui::SetTooltip("%s\n(Enter rebuilds the scene)", spec.help.c_str());
  }
}

void App::drawRunButtons() {
  if (ImGui::Button("Reset (r)")) guarded([&] { resetScene(); });
  recordWidget("reset");
  const char* pause = paused_ ? "Run (space)" : "Pause (space)";
  sameLineIfFits(buttonWidth(pause));
  if (ImGui::Button(pause)) paused_ = !paused_;
  recordWidget("pause");
  sameLineIfFits(buttonWidth("Step (.)"));
  if (ImGui::Button("Step (.)")) keyboard('.');
  recordWidget("step");
  sameLineIfFits(buttonWidth("Rewind (b)"));
  if (ImGui::Button("Rewind (b)")) rewind();
  recordWidget("rewind");
  drawStateFile();
}

// The state now to a scene file and back: the file field, Save and Load.
void App::drawStateFile() {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, "%s", stateFile_.c_str());
  if (ImGui::InputText("state file", buffer, sizeof buffer)) stateFile_ = buffer;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Save state writes the scene as it is now (particles, clock, torn springs,\n"
                                                "wind, integrator and dt) as a scene file; Load state runs one");
  if (ImGui::Button("Save state")) guarded([&] { saveState(); });
  recordWidget("save-state");
  sameLineIfFits(buttonWidth("Load state"));
  if (ImGui::Button("Load state")) guarded([&] { loadState(); });
  recordWidget("load-state");
  const char* record = recording_ ? "Stop recording" : "Record frames";
  sameLineIfFits(buttonWidth(record));
  if (ImGui::Button(record)) guarded([&] { toggleRecording(); });
  recordWidget("record");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("every frame as %s/frame-NNNNNN.png (as --record); a video:\nffmpeg -framerate 60 -i "
                      "%s/frame-%%06d.png -pix_fmt yuv420p out.mp4",
                      recordDirectory().c_str(), recordDirectory().c_str());
}

// --- time stepping ------------------------------------------------------------
void App::drawIntegrationSection() {
  if (!ImGui::CollapsingHeader("Integration", ImGuiTreeNodeFlags_DefaultOpen)) return;
  for (std::size_t k = 0; k < panes_.size(); ++k) drawPaneIntegrator(k);
  drawIntegratorSettings();
  drawTimeControls();
}

// Pane k's integrator, and its dt: one dt for all panes, or one per pane in compare mode.
void App::drawPaneIntegrator(std::size_t k) {
  const auto& table = particles::integratorTable();
  ImGui::PushID(static_cast<int>(k));
  const std::string label = panes_.size() > 1 ? "pane " + std::to_string(k + 1) : "integrator";
  if (ImGui::BeginCombo(label.c_str(), panes_[k]->integratorName())) {
    if (closePopups_) ImGui::CloseCurrentPopup();
    for (std::size_t t = 0; t < table.size(); ++t) {
      if (ImGui::Selectable(table[t].name, static_cast<int>(t) == panes_[k]->integratorIndex())) {
        panes_[k]->setIntegrator(static_cast<int>(t));
        setStatus(integratorLine(static_cast<int>(t)));
      }
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s (order %d)\n%s", table[t].summary, table[t].order, table[t].behaviour);
    }
    ImGui::EndCombo();
  }
  if (k == 0 || panes_.size() > 1) {
    double dt = panes_[k]->dt();
    if (ImGui::InputDouble(panes_.size() > 1 ? "dt" : "dt (s)", &dt, 0.0, 0.0, "%.3e",
                           ImGuiInputTextFlags_EnterReturnsTrue) && dt > 0.0 && std::isfinite(dt)) {
      if (panes_.size() > 1) panes_[k]->setDt(dt);
      else for (auto& pane : panes_) pane->setDt(dt);
    }
  }
  ImGui::PopID();
}

namespace {

// A logarithmic slider over the setting's declared range up to `reach` (a
// slider over 1…100000 could not pick 20); a value typed in (ctrl+click) is
// held to the whole declared range.
bool settingSlider(const char* label, int& value, particles::IntRange range, int reach) {
  if (!ImGui::SliderInt(label, &value, range.min, std::min(reach, range.max), "%d", ImGuiSliderFlags_Logarithmic))
    return false;
  value = std::clamp(value, range.min, range.max);
  return true;
}

}  // namespace

// Schemes with settings of their own: dopri5's error tolerance, xpbd's
// substeps per step, constraint passes per substep and hanging lines solved directly.
void App::drawIntegratorSettings() {
  const auto& table = particles::integratorTable();
  bool anyTolerance = false;
  for (const auto& pane : panes_) anyTolerance |= table[pane->integratorIndex()].usesTolerance;
  if (anyTolerance) {
    float logTolerance = static_cast<float>(std::log10(panes_.front()->integratorSettings().dopri5.tolerance));
    if (ImGui::SliderFloat("log10 step tolerance", &logTolerance, -12.0f, -2.0f, "%.1f")) {
      particles::IntegratorSettings settings = panes_.front()->integratorSettings();
      settings.dopri5.tolerance = std::pow(10.0, static_cast<double>(logTolerance));
      for (auto& pane : panes_) pane->setIntegratorSettings(settings);
    }
  }
  bool anySubsteps = false;
  for (const auto& pane : panes_) anySubsteps |= table[pane->integratorIndex()].usesSubsteps;
  if (anySubsteps) {
    particles::IntegratorSettings settings = panes_.front()->integratorSettings();
    const bool substeps = settingSlider("substeps", settings.xpbd.substeps, particles::XpbdSettings::substepRange, 200);
    const bool iterations =
        settingSlider("iterations", settings.xpbd.iterations, particles::XpbdSettings::iterationRange, 64);
    const bool lines = ImGui::Checkbox("solve hanging lines", &settings.xpbd.lines);
    if (substeps || iterations || lines)
      for (auto& pane : panes_) pane->setIntegratorSettings(settings);
  }
}

// dt scaling, speed, lockstep and the number of compare panes.
void App::drawTimeControls() {
  if (ImGui::Button("dt x2 (+)")) guarded([&] { scaleDt(2.0); });
  sameLineIfFits(buttonWidth("dt /2 (-)"));
  if (ImGui::Button("dt /2 (-)")) guarded([&] { scaleDt(0.5); });
  float speed = static_cast<float>(speed_);
  if (ImGui::SliderFloat("speed", &speed, 0.125f, 8.0f, "%.3gx", ImGuiSliderFlags_Logarithmic)) speed_ = speed;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("simulated seconds per second of frames (60 frames)");
  bool lockstep = stepMode_ == StepMode::Lockstep;
  if (ImGui::Checkbox("lockstep: one step per frame (l)", &lockstep))
    stepMode_ = lockstep ? StepMode::Lockstep : StepMode::FixedTime;
  int paneCount = static_cast<int>(panes_.size());
  if (ImGui::SliderInt("compare panes", &paneCount, 1, 4)) guarded([&] { setPaneCount(paneCount); });
  int threads = particles::threadCount();
  if (ImGui::SliderInt("threads", &threads, 1, std::max(2, particles::affinityCpuCount())))
    particles::setThreadCount(std::max(1, threads));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("threads of the engine's parallel loops (the same results on any count)");
  recordWidget("threads");
}

// --- live plots ---------------------------------------------------------------
void App::drawPlotsSection() {
  if (!ImGui::CollapsingHeader("Energy and constraint error", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const float height = panes_.size() > 1 ? 36.0f : 60.0f;
  for (std::size_t k = 0; k < panes_.size(); ++k) {
    ImGui::PushID(static_cast<int>(k));
    if (panes_.size() > 1) ImGui::TextDisabled("%s", panes_[k]->integratorName());
    plot("energy", "J", panes_[k]->trace().energy(), height);
    plot("max |C|", "m", panes_[k]->trace().constraintError(), height);
    ImGui::PopID();
  }
  ImGui::TextDisabled("x: the last %d frames, newest at the right", Trace::capacity);
}

// --- constraint solver and mouse spring ---------------------------------------
void App::drawSolverSection() {
  if (!ImGui::CollapsingHeader("Solver and mouse spring")) return;
  drawSolverSettings();
  ImGui::Separator();
  drawMouseSpringSettings();
}

void App::drawSolverSettings() {
  particles::SolverSettings settings = panes_.front()->system().solver().settings;
  bool changed = choose("constraint solve", kSolveMethodLabels, settings.method);
  // CG's own settings: the direct solve has no tolerance or iteration cap.
  const bool cg = settings.method == particles::SolveMethod::ConjugateGradient;
  ImGui::BeginDisabled(!cg);
  if (cg) changed |= choose("preconditioner", kPreconditionerLabels, settings.preconditioner);
  float logTolerance = static_cast<float>(std::log10(settings.tolerance));
  if (ImGui::SliderFloat("log10 CG tolerance", &logTolerance, -14.0f, -1.0f, "%.1f")) {
    settings.tolerance = std::pow(10.0, static_cast<double>(logTolerance));
    changed = true;
  }
  changed |= ImGui::InputInt("CG iteration cap", &settings.maxIterations);
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(cg ? "0: 4m + 100 for m constraints" : "conjugate gradient only: the direct solve factorises J W J^T");
  ImGui::EndDisabled();
  changed |= ImGui::InputDouble("feedback k_s", &settings.stiffness, 1.0, 10.0, "%.3g");
  changed |= ImGui::InputDouble("feedback k_d", &settings.damping, 0.5, 5.0, "%.3g");
  if (!changed) return;
  try {
    settings.validate();
    for (auto& pane : panes_) pane->system().solver().settings = settings;
  } catch (const std::exception& e) {
    setStatus(e.what());
  }
}

void App::drawMouseSpringSettings() {
  float frequency = static_cast<float>(mouseSettings_.joint.frequency);
  if (ImGui::SliderFloat("mouse joint f", &frequency, 0.5f, 20.0f, "%.2g Hz", ImGuiSliderFlags_Logarithmic))
    mouseSettings_.joint.frequency = frequency;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("k_s = max(M (2 pi f)^2, R K): M the mass the particle drags along (springs and constraints),\n"
                      "K its springs' stiffness; explicit integrators bound it by sqrt(k_s/m) dt <= 1");
  float ratio = static_cast<float>(mouseSettings_.joint.dampingRatio);
  if (ImGui::SliderFloat("damping ratio", &ratio, 0.0f, 2.0f, "%.2f")) mouseSettings_.joint.dampingRatio = ratio;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("k_d = 2 zeta sqrt(k_s M); 1 is critical (explicit: k_d dt/m <= 1/2)");
  float stiffnessRatio = static_cast<float>(mouseSettings_.joint.stiffnessRatio);
  if (ImGui::SliderFloat("stiffness ratio R", &stiffnessRatio, 0.0f, 50.0f, "%.3g")) mouseSettings_.joint.stiffnessRatio = stiffnessRatio;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("k_s at least R times the grabbed particle's springs: it follows a move within 1/(1 + R)");
}

// --- display ------------------------------------------------------------------
void App::drawDisplaySection() {
  if (!ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::Checkbox("forces (f)", &drawOptions_.forces);
  sameLineIfFits(checkboxWidth("constraints (c)"));
  ImGui::Checkbox("constraints (c)", &drawOptions_.constraints);
  sameLineIfFits(checkboxWidth("help (h)"));
  ImGui::Checkbox("help (h)", &showHelp_);
  // Only the scenes with a closed form have a ghost: elsewhere the box is off and greyed.
  ImGui::BeginDisabled(!exact_);
  bool ghost = exact_ && drawOptions_.ghost;
  if (ImGui::Checkbox("closed-form ghost (g)", &ghost) && exact_) drawOptions_.ghost = ghost;
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip(exact_ ? "the exact motion from the start, beside the simulation"
                             : "this scene has no closed form to show (the oscillator and the pendulum have)");
  ImGui::EndDisabled();
  sameLineIfFits(buttonWidth("frame all (a)"));
  if (ImGui::Button("frame all (a)")) frameAll();
  sameLineIfFits(buttonWidth("scene view (A)"));
  if (ImGui::Button("scene view (A)")) sceneView();
}

}  // namespace demo

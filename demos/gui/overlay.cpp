// Text over the panes: the HUD, the per-pane lines of compare mode, the
// divergence message and the help overlay (key h).
#include <imgui.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <string>

#include "app.h"

namespace demo {

namespace {
// What the mouse does, for the help overlay (the keys come from App::keyBindings()).
struct MouseHelp {
  const char* buttons;
  const char* action;
};
constexpr MouseHelp mouseHelp[] = {
    {"left drag", "pull a particle with a mouse spring"},
    {"right drag, shift+left", "pin a particle and move it; click a pinned one to unpin"},
};

constexpr ImGuiWindowFlags overlayFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                          ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                          ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char buffer[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buffer, sizeof buffer, fmt, args);
  va_end(args);
  return buffer;
}

ImU32 hudColour() {
  const Rgb c = palette::hudText;
  return IM_COL32(c.r, c.g, c.b, 255);
}

// Text on a dark box, drawn over everything; returns the box.
PixelRect boxedText(const ImVec2& at, const std::string& text, ImU32 colour) {
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const ImVec2 size = ImGui::CalcTextSize(text.c_str());
  draw->AddRectFilled(at, ImVec2(at.x + size.x + 12, at.y + size.y + 8), IM_COL32(10, 12, 16, 200), 4.0f);
  draw->AddText(ImVec2(at.x + 6, at.y + 4), colour, text.c_str());
  return {static_cast<int>(at.x), static_cast<int>(at.y), static_cast<int>(size.x) + 13, static_cast<int>(size.y) + 9};
}

// The rectangle of the current ImGui window.
PixelRect windowRect() {
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  return {static_cast<int>(at.x), static_cast<int>(at.y), static_cast<int>(size.x) + 1, static_cast<int>(size.y) + 1};
}
}  // namespace

void App::drawHud() {
  if (panes_.size() > 1) {
    drawPaneLines();
  } else {
    const Simulation& sim = *panes_.front();
    const particles::ParticleSystem& s = sim.system();
    const PixelRect area = worldArea();
    // Bottom left: the scenes hang from rails at the top of the view.
    ImGui::SetNextWindowPos(ImVec2(area.x + 8.0f, area.y + area.height - 8.0f), ImGuiCond_Always, ImVec2(0.0f, 1.0f));
    ImGui::SetNextWindowBgAlpha(0.65f);
    ImGui::Begin("##hud", nullptr, overlayFlags);
    ImGui::TextColored(ImVec4(1.0f, 0.85f, 0.45f, 1.0f), "%s", scene_.label.c_str());
    ImGui::SameLine();
    ImGui::Text("  t = %.2f s%s", s.time(), paused_ ? "   [paused]" : "");
    ImGui::Text("%s   dt %g   %d substep%s/frame%s", sim.integratorName(), sim.dt(), sim.lastFrame().substeps,
                sim.lastFrame().substeps == 1 ? "" : "s",
                stepMode_ == StepMode::Lockstep ? " (lockstep)" : sim.lastFrame().capped ? " (capped: slow motion)" : "");
    // Fixed-width numbers, so the auto-sized box does not change size from frame to frame.
    ImGui::Text("simulation %7.2f ms   draw %6.1f ms   per frame", sim.lastFrame().simulationMs, drawMs_);
    // The last step's statistics: every solve of it, not only the last one.
    const particles::StepStats& step = s.lastStepStats();
    if (step.cgIterations == 0)
      ImGui::Text("%d particles   %d solve%s, residual %.1e", s.size(), step.solves, step.solves == 1 ? "" : "s",
                  step.maxResidual);
    else
      ImGui::Text("%d particles   %d solve%s, CG %d iterations, residual %.1e", s.size(), step.solves,
                  step.solves == 1 ? "" : "s", step.cgIterations, step.maxResidual);
    ImGui::Text("max |C| %.2e   energy % .5e", s.maxConstraintError(), s.totalEnergy());
    ImGui::TextDisabled("h help   p panel   v compare");
    overlays_.push_back({"hud", windowRect()});
    ImGui::End();
  }
  if (statusFrames_ > 0) {
    const PixelRect area = worldArea();
    const float width = ImGui::CalcTextSize(status_.c_str()).x + 12.0f;
    overlays_.push_back(
        {"status", boxedText(ImVec2(area.x + 0.5f * (area.width - width), area.y + 8.0f), status_, hudColour())});
  }
}

// Which colour is which force type, for the types present in the first pane.
void App::drawForceLegend() {
  const particles::ParticleSystem& s = panes_.front()->system();
  std::vector<std::string> types;
  for (const auto& force : s.forceObjects())
    if (std::find(types.begin(), types.end(), force->type()) == types.end()) types.push_back(force->type());
  const PixelRect area = worldArea();
  ImGui::SetNextWindowPos(ImVec2(area.x + area.width - 8.0f, area.y + area.height - 8.0f), ImGuiCond_Always,
                          ImVec2(1.0f, 1.0f));
  ImGui::SetNextWindowBgAlpha(0.65f);
  ImGui::Begin("##legend", nullptr, overlayFlags);
  ImGui::TextDisabled("force arrows (f)");
  auto entry = [](const char* name, Rgb c) {
    ImGui::TextColored(ImVec4(c.r / 255.f, c.g / 255.f, c.b / 255.f, 1.f), "-->");
    ImGui::SameLine();
    ImGui::TextUnformatted(name);
  };
  for (const std::string& type : types) entry(type.c_str(), forceArrowColour(type.c_str()));
  if (!s.constraints().empty()) entry("constraint force J^T lambda", palette::constraintForceArrow);
  overlays_.push_back({"legend", windowRect()});
  ImGui::End();
}

void App::drawPaneLines() {
  const std::vector<ViewTransform> views = paneViews();
  for (std::size_t k = 0; k < panes_.size(); ++k) {
    const Simulation& sim = *panes_[k];
    const particles::ParticleSystem& s = sim.system();
    std::string text = format("%s   dt %g   %.2f ms/frame\nE % .5e   max |C| %.1e", sim.integratorName(), sim.dt(),
                              sim.lastFrame().simulationMs, s.totalEnergy(), s.maxConstraintError());
    if (k == 0) text = scene_.label + format("   t = %.2f s%s", s.time(), paused_ ? "   [paused]" : "") + "\n" + text;
    const PixelRect& p = views[k].pane;
    ImGui::GetForegroundDrawList()->PushClipRect(ImVec2(p.x, p.y), ImVec2(p.x + p.width, p.y + p.height), true);
    overlays_.push_back({"pane-hud", boxedText(ImVec2(p.x + 6.0f, p.y + 6.0f), text, hudColour())});
    ImGui::GetForegroundDrawList()->PopClipRect();
  }
}

void App::drawDivergenceMessages() {
  const std::vector<ViewTransform> views = paneViews();
  for (std::size_t k = 0; k < panes_.size(); ++k) {
    if (!panes_[k]->stopped()) continue;
    const std::string text =
        panes_[k]->divergedAt()
            ? format("diverged at t = %.3f s: press r to reset or b to rewind", *panes_[k]->divergedAt())
            : *panes_[k]->refusal() + "\npress i for another integrator";
    const ImVec2 size = ImGui::CalcTextSize(text.c_str());
    const PixelRect& p = views[k].pane;
    const ImVec2 at(p.x + 0.5f * (p.width - size.x) - 6, p.y + 0.5f * p.height - 14);
    const Rgb c = palette::divergenceText;
    overlays_.push_back({"divergence", boxedText(at, text, IM_COL32(c.r, c.g, c.b, 255))});
    ImGui::GetForegroundDrawList()->AddRect(at, ImVec2(at.x + size.x + 12, at.y + size.y + 8),
                                            IM_COL32(c.r, c.g, c.b, 255), 4.0f, 0, 1.5f);
  }
}

void App::drawHelp() {
  const PixelRect area = worldArea();
  ImGui::SetNextWindowPos(ImVec2(area.x + 0.5f * area.width, area.y + 0.5f * area.height), ImGuiCond_Always,
                          ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowBgAlpha(0.88f);
  ImGui::Begin("Keys", nullptr, overlayFlags & ~ImGuiWindowFlags_NoTitleBar);
  if (ImGui::BeginTable("keys", 2)) {
    auto row = [](const char* keys, const char* action) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextColored(ImVec4(1.0f, 0.85f, 0.45f, 1.0f), "%s", keys);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(action);
    };
    row("1, 2, ...", "load a scene (listed below)");
    for (const KeyBinding& k : keyBindings())
      if (k.label) row(k.label, k.help);
    for (const MouseHelp& m : mouseHelp) row(m.buttons, m.action);
    ImGui::EndTable();
  }
  ImGui::Separator();
  for (const SceneKey& k : sceneKeys()) {
    ImGui::Text("%c  %s", k.key, k.choice.label.c_str());
  }
  overlays_.push_back({"help", windowRect()});
  ImGui::End();
}

}  // namespace demo

// Wind and tearing in the demo: keys w and t and the panel's section, the
// same settings pushed to every pane (particles/forces/wind.h, particles/tearing.h).
#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "app.h"
#include "output/format_number.h"
#include "particles/constants.h"
#include "particles/tearing.h"

namespace demo {

namespace {
constexpr double kDegrees = 180.0 / particles::kPi;

std::string describeWind(const particles::WindSettings& w) {
  return "wind " + output::formatGeneral(w.speed, 3) + " m/s at " + output::formatGeneral(w.direction * kDegrees, 3) +
         " deg, gusts +-" + output::formatGeneral(100.0 * w.gust, 3) + "%";
}
}  // namespace

// A new scene brings its own: the wind that blows in it (a --param wind=…
// or a scene file's), its tear strain; the panel keeps its wind settings for
// w when the scene has none.
void App::takeWindTearFromScene() {
  const Simulation& first = *panes_.front();
  windTear_.windOn = first.wind() != nullptr;
  if (first.wind()) windTear_.wind = first.wind()->settings();
  const double strain = first.system().tearing().strain;
  windTear_.tearOn = strain > 0.0;
  if (strain > 0.0) windTear_.tearStrain = strain;
}

void App::applyWindTear() {
  for (auto& pane : panes_) {
    if (pane->takesWind())
      pane->setWind(windTear_.windOn ? std::optional<particles::WindSettings>(windTear_.wind) : std::nullopt);
    pane->setTearStrain(windTear_.tearOn ? windTear_.tearStrain : 0.0);
  }
}

void App::toggleWind() {
  if (!panes_.front()->takesWind()) {
    setStatus("wind blows on the cloth and the hair: this scene has no edges for it");
    return;
  }
  windTear_.windOn = !windTear_.windOn;
  applyWindTear();
  setStatus(windTear_.windOn ? describeWind(windTear_.wind) + " (w: off; the panel sets it)" : "wind off");
}

void App::toggleTearing() {
  windTear_.tearOn = !windTear_.tearOn;
  applyWindTear();
  setStatus(windTear_.tearOn ? "tearing: springs stretched beyond " +
                                   output::formatGeneral(100.0 * windTear_.tearStrain, 3) + "% of their rest length break"
                             : "tearing off (torn springs stay torn until r)");
}

namespace {
// A slider over a double shown in units of `scale`; true when it moved.
bool slider(const char* label, double& value, float lo, float hi, const char* format, const char* tooltip = nullptr,
            double scale = 1.0, ImGuiSliderFlags flags = 0) {
  float shown = static_cast<float>(value * scale);
  const bool moved = ImGui::SliderFloat(label, &shown, lo, hi, format, flags);
  if (moved) value = shown / scale;
  if (tooltip && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tooltip);
  return moved;
}
}  // namespace

// The section's header says what is on, so that it reads right even closed:
// "Wind and tearing: wind 5 m/s, tearing beyond 50%". Open by default when
// the scene starts with either on.
void App::drawWindTearSection() {
  const Simulation& first = *panes_.front();
  std::string on;
  if (windTear_.windOn && first.takesWind()) on = "wind " + output::formatGeneral(windTear_.wind.speed, 3) + " m/s";
  if (windTear_.tearOn)
    on += (on.empty() ? "" : ", ") + std::string("tearing beyond ") +
          output::formatGeneral(100.0 * windTear_.tearStrain, 3) + "%";
  const std::string header = "Wind and tearing: " + (on.empty() ? std::string("off") : on) + "###wind-and-tearing";
  const bool open = ImGui::CollapsingHeader(header.c_str(), windTear_.windOn || windTear_.tearOn
                                                                ? ImGuiTreeNodeFlags_DefaultOpen
                                                                : ImGuiTreeNodeFlags_None);
  recordWidget("wind-and-tearing");
  if (!open) return;
  particles::WindSettings& w = windTear_.wind;
  const ImGuiSliderFlags logarithmic = ImGuiSliderFlags_Logarithmic;
  bool changed = ImGui::Checkbox("wind (w)", &windTear_.windOn);
  changed |= slider("speed", w.speed, 0.0f, 20.0f, "%.3g m/s");
  changed |= slider("direction", w.direction, -180.0f, 180.0f, "%.0f deg",
                    "the way the air moves, counter-clockwise from +x (0: to the right)", kDegrees);
  changed |= slider("drag c", w.drag, 1e-3f, 1.0f, "%.3g",
                    "an edge across the wind takes c |edge| u_n^2, N per m per (m/s)^2", 1.0, logarithmic);
  changed |= slider("gust", w.gust, 0.0f, 1.0f, "%.2f", "the speed swings between (1 - gust) and (1 + gust) times its mean");
  changed |= slider("gust period", w.gustPeriod, 0.2f, 10.0f, "%.3g s", "the slowest gust's period", 1.0, logarithmic);
  if (ImGui::InputInt("gust seed", &w.seed)) {
    w.seed = std::max(0, w.seed);
    changed = true;
  }
  ImGui::Separator();
  changed |= ImGui::Checkbox("tearing (t)", &windTear_.tearOn);
  changed |= slider("tear strain", windTear_.tearStrain, 0.02f, 2.0f, "%.3g",
                    "a spring stretched beyond this fraction of its rest length breaks", 1.0, logarithmic);
  // Live: the air this step (gusts included) and the links torn so far.
  if (const particles::WindForce* wind = first.wind())
    ImGui::Text("air now %.3g m/s at %.0f deg", wind->air().norm(), std::atan2(wind->air().y(), wind->air().x()) * kDegrees);
  else
    ImGui::TextDisabled(first.takesWind() ? "no wind blows (w)" : "this scene has no edges for the wind");
  ImGui::Text("%s torn", output::plural(static_cast<long long>(first.system().brokenLinks().size()), "link").c_str());
  if (changed) guarded([&] { applyWindTear(); });
}

}  // namespace demo

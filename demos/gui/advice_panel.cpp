// The control panel's Advice section: `particle-lab advise` for the current
// scene (advice_job.h), its progress, the table of picks and one-click Apply.
#include <imgui.h>

#include <cmath>
#include <cstdio>

#include "app.h"
#include "panel_rows.h"
#include "output/format_number.h"

namespace demo {

namespace {
std::string cell(double value) { return std::isfinite(value) ? lab::general(value, 3) : "-"; }

// One integrator's row of the picks table: its name (green for the cheapest),
// then its dt or tolerance, error and cost, or why it has none.
void drawPickRow(const lab::IntegratorSurvey& scan, const lab::Pick& p, bool best, int repeats) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  if (best) ImGui::TextColored(ImVec4(0.4f, 1.0f, 0.4f, 1.0f), "%s", scan.integrator.c_str());
  else ImGui::TextUnformatted(scan.integrator.c_str());
  ImGui::TableNextColumn();
  if (!scan.refused.empty()) {
    ImGui::TextDisabled("refuses");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", scan.refused.c_str());
    return;
  }
  if (!p.found && !p.uncertified.empty()) {
    ImGui::TextDisabled("uncertified");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.uncertified.c_str());
    return;
  }
  if (!p.found) {
    ImGui::TextDisabled("none");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("nothing within E on the scanned grid (%s)",
                        output::plural(static_cast<long long>(scan.scanned.size()), "run").c_str());
    return;
  }
  // An adaptive scheme's dt is its call interval; its tolerance sets the steps.
  ImGui::TextUnformatted(scan.adaptive ? ("tol " + cell(p.candidate.tolerance)).c_str() : cell(p.candidate.dt).c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s %s s; certified margin %s to %s (%s)",
                      scan.adaptive ? "called every" : "coarse scan's largest surviving dt",
                      cell(scan.adaptive ? p.candidate.dt : scan.safeDt).c_str(), cell(p.certifiedLo).c_str(),
                      cell(p.certifiedHi).c_str(), p.certified() ? lab::boundText(p.marginRuns).c_str() : "-");
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(cell(p.error()).c_str());
  ImGui::TableNextColumn();
  ImGui::TextUnformatted((cell(p.cpuPerSimulatedSecond) + (p.tie ? " (tie)" : "")).c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("median of %s (interleaved across the picks), %s to %s%s",
                      output::plural(repeats, "repeat").c_str(), cell(p.cpuMin).c_str(), cell(p.cpuMax).c_str(),
                      p.tie ? "; overlaps the cheapest's range: a tie" : "");
}

void drawPicksTable(const lab::Advice& a, int repeats) {
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
  if (!ImGui::BeginTable("picks", 4, flags)) return;
  for (const char* column : {"integrator", "dt / tol", "max error", "CPU s/sim s"}) ImGui::TableSetupColumn(column);
  ImGui::TableHeadersRow();
  for (std::size_t k = 0; k < a.picks.size(); ++k)
    drawPickRow(a.survey.integrators[k], a.picks[k], static_cast<int>(k) == a.best, repeats);
  ImGui::EndTable();
}
}  // namespace

void App::drawAdvicePanel() {
  const bool open = ImGui::CollapsingHeader("Advice: cheapest integrator within an error");
  recordWidget("advice");
  if (!open) return;
  if (const char* why = AdviceJob::unavailable()) {
    ImGui::TextWrapped("%s", why);
    return;
  }
  drawAdviceRequest();
  const bool running = advice_.running();
  drawAdviceButtons(running);
  if (running) {
    char label[64];
    std::snprintf(label, sizeof label, advice_.cancelling() ? "cancelling" : "%.0f%%", 100.0 * advice_.progress());
    ImGui::ProgressBar(static_cast<float>(advice_.progress()), ImVec2(-1.0f, 0.0f), label);
    return;
  }
  if (advice_.state() == AdviceState::Cancelled) ImGui::TextDisabled("cancelled");
  if (advice_.state() == AdviceState::Failed) ImGui::TextWrapped("failed: %s", advice_.message().c_str());
  if (advice_.state() == AdviceState::Done) drawAdviceResult();
}

// What is asked: the error E over the horizon T.
void App::drawAdviceRequest() {
  ImGui::TextWrapped("Measures a copy of this scene as particle-lab advise --max-steps %ld --repeats %d does: a "
                     "reference, then per integrator the largest safe dt within E over [0, T], timed.",
                     adviceRequest_.maxSteps, adviceRequest_.repeats);
  ImGui::InputDouble("E (world units)", &adviceRequest_.error, 0.0, 0.0, "%.3g");
  recordWidget("advise-error");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("largest particle position error allowed over [0, T]");
  ImGui::InputDouble("T (s)", &adviceRequest_.horizon, 0.0, 0.0, "%.3g");
  recordWidget("advise-horizon");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("simulated seconds the error is measured over");
}

// The three buttons keep their places whatever the job's state (scripts click them).
void App::drawAdviceButtons(bool running) {
  ImGui::BeginDisabled(running);
  if (ImGui::Button("Advise")) guarded([&] { startAdvice(); });
  ImGui::EndDisabled();
  recordWidget("advise");
  sameLineIfFits(buttonWidth("Cancel"));
  ImGui::BeginDisabled(!running || advice_.cancelling());
  if (ImGui::Button("Cancel")) advice_.cancel();
  ImGui::EndDisabled();
  recordWidget("advise-cancel");
  sameLineIfFits(buttonWidth("Apply"));
  const bool applicable = advice_.state() == AdviceState::Done && advice_.advice().best >= 0 && adviceIsForThisScene();
  ImGui::BeginDisabled(!applicable);
  if (ImGui::Button("Apply")) guarded([&] { applyAdvice(); });
  ImGui::EndDisabled();
  recordWidget("advise-apply");
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("sets pane 1's integrator, dt and tolerance to the cheapest pick");
}

// A finished survey: what was measured, the picks, and the cheapest one's options.
void App::drawAdviceResult() {
  const lab::Advice& a = advice_.advice();
  ImGui::TextWrapped("%s, %s, T = %s s, E = %s; reference: %s%s", advice_.scene().label.c_str(),
                     output::plural(a.survey.particles, "particle").c_str(), lab::general(advice_.request().horizon).c_str(),
                     lab::general(advice_.request().error).c_str(), a.survey.reference.c_str(),
                     adviceIsForThisScene() ? "" : " (another scene: advise again to apply)");
  drawPicksTable(a, advice_.request().repeats);
  if (!a.survey.limit.empty())
    ImGui::TextWrapped("cannot certify: %s (longest horizon it can: %.4g s)", a.survey.limit.c_str(),
                       a.survey.certifiableHorizon);
  else if (a.best < 0)
    ImGui::TextWrapped("no integrator meets E over T within its safe range");
  else ImGui::TextWrapped("cheapest: %s", lab::pickArguments(a.picks[a.best].candidate).c_str());
}

}  // namespace demo

#include "state_log.h"

#include <algorithm>
#include <stdexcept>

#include "output/output_file.h"
#include "particles/tearing.h"

namespace demo {

namespace {

// The pane's mouse joint (while a particle is held), its wind (while it
// blows) and its tearing.
void writeWindTearGrab(std::ostream& out, std::size_t k, const Simulation& sim) {
  if (const particles::MouseSpringForce* spring = sim.mouseSpring()) {
    const Eigen::Vector2d mean = sim.grabbedMean();
    out << "grab," << k << "," << spring->particle() << "," << spring->target().x() << "," << spring->target().y()
        << "," << spring->stiffness() << "," << spring->damping() << "," << sim.grabbedFrames() << "," << mean.x()
        << "," << mean.y() << "\n";
  }
  if (const particles::WindForce* wind = sim.wind()) {
    const particles::WindSettings& w = wind->settings();
    out << "wind," << k << "," << w.speed << "," << w.direction << "," << w.drag << "," << w.gust << ","
        << w.gustPeriod << "," << w.seed << "," << wind->air().x() << "," << wind->air().y() << "\n";
  }
  out << "tearing," << k << "," << sim.system().tearing().strain << "," << sim.system().brokenLinks().size() << "\n";
}

// One pane: its state, view, faces, particles and walls.
void writePaneRecords(std::ostream& out, std::size_t k, const PaneState& pane) {
  const Simulation& sim = *pane.simulation;
  const particles::ParticleSystem& s = sim.system();
  int springs = 0;
  for (const auto& f : s.forceObjects()) springs += dynamic_cast<const particles::MouseSpringForce*>(f.get()) != nullptr;
  out << "pane," << k << "," << pane.sceneLabel << "," << sim.integratorName() << "," << sim.dt() << ","
      << s.time() << "," << sim.steps() << "," << (sim.divergedAt() ? 1 : 0) << "," << springs << ","
      << sim.sceneEnergy() << "," << s.maxConstraintError() << "," << sim.mouseSpringEnergy() << ","
      << (sim.lastFrame().capped ? 1 : 0) << "," << sim.lastFrame().substeps << "," << sim.frames() << "," << sim.owedTime() << ","
      << sim.trace().energy().size() << "," << (sim.lastFrame().waited ? 1 : 0) << "," << sim.lastFrame().longestStepMs
      << "," << sim.framesWaited() << "," << (sim.trace().energy().empty() ? 0.0f : sim.trace().energy().back()) << ","
      << (sim.trace().constraintError().empty() ? 0.0f : sim.trace().constraintError().back()) << "\n";
  const Renderer::PaneDrawing& faces = pane.drawing;
  out << "faces," << k << "," << faces.shaded << "," << faces.leftOut << "," << faces.shadedPixels << ","
      << faces.panePixels << "," << faces.spacingPixels << "," << (faces.springsDrawn ? 1 : 0) << ","
      << (faces.particlesDrawn ? 1 : 0) << "," << faces.drawnFraction << "\n";
  const ViewTransform& v = pane.view;
  out << "view," << k << "," << v.pane.x << "," << v.pane.y << "," << v.pane.width << "," << v.pane.height << ","
      << v.worldMin.x() << "," << v.worldMin.y() << "," << v.worldMax.x() << "," << v.worldMax.y() << "\n";
  for (int i = 0; i < s.size(); ++i) {
    const Eigen::Vector2d x = s.position(i), u = s.velocity(i);
    out << "particle," << k << "," << i << "," << x.x() << "," << x.y() << "," << u.x() << "," << u.y() << ","
        << s.masses()[i] << "," << (s.pinned(i) ? 1 : 0) << "\n";
  }
  for (const particles::Collider& c : s.colliders()) {
    Eigen::Vector2d lo, hi;  // a bounded collider's bounding box; a half-plane has none
    if (c.bounds(lo, hi)) out << "wall," << k << "," << lo.x() << "," << lo.y() << "," << hi.x() << "," << hi.y() << "\n";
  }
  writeWindTearGrab(out, k, sim);
}

void writeStateRecords(std::ostream& out, const std::vector<PaneState>& panes, const StateExtras& extras,
                       long long frames, bool paused) {
  out.precision(17);
  out << "# particle-demo state at exit; format in demos/gui/state_log.h\n";
  out << "frame," << frames << "\npaused," << (paused ? 1 : 0) << "\n";
  for (std::size_t k = 0; k < panes.size(); ++k) writePaneRecords(out, k, panes[k]);
  for (const Overlay& o : extras.overlays) {
    std::string text;
    for (char c : o.text) text += c == '\n' ? std::string(" | ") : std::string(1, c);
    out << "overlay," << o.kind << "," << o.rect.x << "," << o.rect.y << "," << o.rect.width << "," << o.rect.height
        << "," << text << "\n";
    out << "text-fit," << o.kind << "," << o.textWidth << "," << o.textHeight << "," << (o.shortened ? 1 : 0) << "\n";
  }
  for (const Overlay& w : extras.widgets)
    out << "widget," << w.kind << "," << w.rect.x << "," << w.rect.y << "," << w.rect.width << "," << w.rect.height
        << "\n";
  // Frame times after a warm-up of 10 frames: median and spread.
  auto quantile = [](std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    auto k = v.begin() + static_cast<long>(q * (v.size() - 1));
    std::nth_element(v.begin(), k, v.end());
    return *k;
  };
  const std::size_t warmUp = std::min<std::size_t>(10, extras.frameMs.size());
  const std::vector<double> ms(extras.frameMs.begin() + warmUp, extras.frameMs.end());
  const std::vector<double> stepping(extras.frameSimulationMs.begin() + std::min(warmUp, extras.frameSimulationMs.size()),
                                     extras.frameSimulationMs.end());
  out << "frame-times," << ms.size() << "," << quantile(ms, 0.5) << "," << quantile(ms, 0.1) << "," << quantile(ms, 0.9)
      << "," << quantile(stepping, 0.5) << "\n";
  const FrameBudget& budget = extras.lastBudget;
  const BudgetTally& t = extras.budgetTally;
  out << "budget," << budget.budgetMs << "," << budget.steps << "," << budget.panesStepped << "," << budget.panesWaiting << ","
      << (budget.stepOverBudget() ? 1 : 0) << "," << budget.steppingMs << "," << budget.longestStepMs << "," << t.frames << ","
      << t.spent << "," << t.withPaneWaiting << "," << t.withStepOverBudget << "," << t.overByMoreThanAStep << ","
      << t.largestSteppingMs << "," << t.largestStepMs << "\n";
  out << "real-time," << extras.realTime.lastSecond << "," << extras.realTime.simSeconds << ","
      << extras.realTime.wallSeconds << "," << (extras.realTime.paced ? 1 : 0) << "\n";
  const AdviceRecord& a = extras.advice;
  out << "advice," << a.state << "," << a.progress << "," << a.integrator << "," << a.dt << "," << a.tolerance << ","
      << a.framesWhileRunning << "," << a.applied << "\n";
  const BuildRecord& b = extras.build;
  out << "build," << (b.active ? 1 : 0) << "," << b.tool << "," << b.selection << "," << b.historyState << ","
      << b.historyStates << "," << b.gesturePoints << "," << b.grid << "," << b.file << "\n";
  out << "timing," << extras.sceneDrawMs << "," << extras.overlayDrawMs << "," << (extras.panelShown ? 1 : 0) << ","
      << extras.overlayDrawSamples.size() << "," << quantile(extras.sceneDrawSamples, 0.5) << ","
      << quantile(extras.overlayDrawSamples, 0.5) << "," << quantile(extras.overlayDrawSamples, 0.1) << ","
      << quantile(extras.overlayDrawSamples, 0.9) << "\n";
}

}  // namespace

std::string writeStateFile(const std::string& path, const std::vector<PaneState>& panes,
                           const StateExtras& extras, long long frames, bool paused) {
  try {
    output::OutputFile file(path, "--log-state");
    writeStateRecords(file.stream(), panes, extras, frames, paused);
    file.close();
    return "";
  } catch (const std::exception& e) {  // cannot open (std::invalid_argument) or write (output::WriteError)
    return e.what();
  }
}

}  // namespace demo

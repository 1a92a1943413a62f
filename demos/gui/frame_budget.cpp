#include "frame_budget.h"

#include <algorithm>
#include <chrono>

namespace demo {

namespace {
// The pane that owes a step and is furthest behind in simulated time (the
// first such in pane order on a tie), or nullptr.
Simulation* furthestBehind(const std::vector<Simulation*>& panes) {
  Simulation* next = nullptr;
  for (Simulation* pane : panes)
    if (pane->owesStep() && (!next || pane->system().time() < next->system().time())) next = pane;
  return next;
}
}  // namespace

FrameBudget stepPanesWithinBudget(const std::vector<Simulation*>& panes, double frameTime, StepMode mode,
                                  double budgetMs) {
  FrameBudget frame;
  frame.budgetMs = budgetMs;
  for (Simulation* pane : panes) pane->beginFrame(frameTime, mode);
  const auto start = std::chrono::steady_clock::now();
  auto elapsedMs = [&] {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };
  while (Simulation* pane = furthestBehind(panes)) {
    if (frame.steps > 0 && elapsedMs() >= budgetMs) {
      frame.spent = true;
      break;
    }
    frame.longestStepMs = std::max(frame.longestStepMs, pane->takeStep());
    ++frame.steps;
  }
  frame.steppingMs = elapsedMs();
  for (Simulation* pane : panes) {
    pane->endFrame(frame.spent);
    frame.panesStepped += pane->lastFrame().substeps > 0;
    frame.panesWaiting += pane->lastFrame().waited;
  }
  return frame;
}

void BudgetTally::add(const FrameBudget& frame) {
  if (frame.steps == 0) return;
  ++frames;
  spent += frame.spent;
  withPaneWaiting += frame.panesWaiting > 0;
  withStepOverBudget += frame.stepOverBudget();
  overByMoreThanAStep += frame.steppingMs > frame.budgetMs + frame.longestStepMs;
  largestSteppingMs = std::max(largestSteppingMs, frame.steppingMs);
  largestStepMs = std::max(largestStepMs, frame.longestStepMs);
}

}  // namespace demo

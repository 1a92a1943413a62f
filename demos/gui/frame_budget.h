#pragma once
// The wall time a frame may spend stepping, shared by every pane. Panes step
// in turns, the one furthest behind in simulated time first (so compare panes
// keep one clock), until each has stepped its share of the frame or the
// budget is spent. The budget is checked before each step and a frame always
// takes at least one, so no frame's stepping passes the budget by more than
// the one step begun within it: a scene whose single step takes longer than
// the budget runs one step a frame, and compare panes not reached in a frame
// wait for the next (both slow motion, said in the HUD and the state log).
#include <vector>

#include "simulation.h"

namespace demo {

// The stepping budget of a frame unless --step-budget sets another, ms.
constexpr double defaultStepBudgetMs = 40.0;

// What one frame's stepping did.
struct FrameBudget {
  double budgetMs = defaultStepBudgetMs;
  double steppingMs = 0.0;     // wall time spent stepping, every pane
  double longestStepMs = 0.0;  // the frame's longest single step
  int steps = 0;               // steps taken, every pane
  int panesStepped = 0;        // panes that took at least one step
  int panesWaiting = 0;        // panes that owed a step and took none: the budget was spent first
  bool spent = false;          // the budget ran out with steps still owed (slow motion)
  // A single step took longer than the whole budget.
  bool stepOverBudget() const { return longestStepMs > budgetMs; }
};

// Frames stepped since the start, counted by what their budget did.
struct BudgetTally {
  long long frames = 0;               // frames that took a step
  long long spent = 0;                // the budget ran out with steps still owed
  long long withPaneWaiting = 0;      // a pane owed a step and took none
  long long withStepOverBudget = 0;   // a single step took longer than the budget
  long long overByMoreThanAStep = 0;  // stepping passed the budget by more than the frame's longest step
  double largestSteppingMs = 0.0, largestStepMs = 0.0;
  void add(const FrameBudget& frame);
};

// Steps the panes through one frame of frameTime simulated seconds (or one
// step each in lockstep) within budgetMs of wall time.
FrameBudget stepPanesWithinBudget(const std::vector<Simulation*>& panes, double frameTime, StepMode mode,
                                  double budgetMs);

}  // namespace demo

#pragma once
// The experiment subcommands of `particle-lab`.
#include <string>

#include "lab/lab.h"

namespace lab {

struct StabilityOptions {
  double duration = 60.0;  // T of Tables 1 and 2, simulated seconds a run must survive
  static constexpr double minDuration = 1.0, maxDuration = 1e4;  // accepted range of --duration, s
  // Table 2: the per-run failure probability its runs must bound (failure_bound.h); 0: the plan's starts.
  double failureBound = 0.0;
  static constexpr double minFailureBound = 1e-5, maxFailureBound = 0.5;  // accepted range of --failure-bound
};
int runStability(const LabOptions& options, const StabilityOptions& stability);

struct TimingOptions {
  int repeats = 5;  // timed repeats; the median is reported
  int steps = 10;   // steps per repeat
};
int runTiming(const LabOptions& options, const TimingOptions& timing);

int runAccuracy(const LabOptions& options);
int runExtremes(const LabOptions& options);
int runClaims(const LabOptions& options);
int runCost(const LabOptions& options);
int runLongtime(const LabOptions& options);
int runSmallSteps(const LabOptions& options);

// Wall time of one step (seconds: the median over `repeats` of the mean of
// `steps` timed steps, with the smallest and largest of those repeats), and
// mean CG iterations and solves per step (StepStats), after warm-up steps. A
// step that leaves the state non-finite is not counted and the scene is
// restored to its warmed-up state.
struct StepCost {
  double seconds = 0.0;
  double cgIterations = 0.0;
  double solves = 0.0;
  double minSeconds = 0.0, maxSeconds = 0.0;  // the spread of the repeats
  // CG iterations per solve (0 without solves).
  double cgIterationsPerSolve() const { return solves > 0.0 ? cgIterations / solves : 0.0; }
};
// The fields a cell's result keeps (lab/cell_json.h).
template <class Io>
void fields(Io& io, StepCost& c) {
  io("seconds", c.seconds), io("cg_iterations", c.cgIterations), io("solves", c.solves);
  io("min_seconds", c.minSeconds), io("max_seconds", c.maxSeconds);
}
StepCost measureStepCost(scenes::Scene& scene, const std::string& integrator, double dt,
                         const TimingOptions& timing);

// One configuration timed beside others: a scene, its integrator and dt.
struct TimedStep {
  scenes::Scene scene;
  std::string integrator;
  double dt = 0.0;
};
// The step costs of several configurations measured interleaved: repeat 1 of
// each, then repeat 2 of each, ..., so that a change of load on the machine
// falls on all of them alike and their ratios stay meaningful.
std::vector<StepCost> measureInterleaved(std::vector<TimedStep>& configurations, const TimingOptions& timing);

// "median (min–max)" of a step cost in milliseconds or microseconds (scale 1e3, 1e6).
std::string costText(const StepCost& cost, double scale);

// A rough CPU time of a run of `duration` at `dt` (from a few timed steps; 0
// when they fail): what a sweep orders its cells' start by (parallel.h).
double estimatedRunSeconds(scenes::Scene scene, const std::string& integrator, double dt, double duration);

}  // namespace lab

#pragma once
// The experiment subcommands of `particle-lab`.
#include <string>

#include "lab/lab.h"

namespace lab {

struct StabilityOptions {
  double duration = 60.0;  // T of Tables 1 and 2, simulated seconds a run must survive
  static constexpr double minDuration = 1.0, maxDuration = 1e4;  // accepted range of --duration, s
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

// Median wall time of one step (seconds), and mean CG iterations and solves
// per step (StepStats) of a scene under an integrator: warm-up steps, then
// `repeats` × `steps` timed steps. A step that leaves the state non-finite is
// not counted and the scene is restored to its warmed-up state.
struct StepCost {
  double seconds = 0.0;
  double cgIterations = 0.0;
  double solves = 0.0;
  // CG iterations per solve (0 without solves).
  double cgIterationsPerSolve() const { return solves > 0.0 ? cgIterations / solves : 0.0; }
};
// The fields a cell's result keeps (lab/cell_json.h).
template <class Io>
void fields(Io& io, StepCost& c) {
  io("seconds", c.seconds), io("cg_iterations", c.cgIterations), io("solves", c.solves);
}
StepCost measureStepCost(scenes::Scene& scene, const std::string& integrator, double dt,
                         const TimingOptions& timing);

// A rough CPU time of a run of `duration` at `dt` (from a few timed steps; 0
// when they fail): what a sweep orders its cells' start by (parallel.h).
double estimatedRunSeconds(scenes::Scene scene, const std::string& integrator, double dt, double duration);

}  // namespace lab

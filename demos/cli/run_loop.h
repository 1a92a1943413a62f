#pragma once
// The runner's step loop (particle-lab run), one step at a time, so that
// the tests drive exactly the code the runner does:
//   step → diagnostics (once, every diagnosticsEvery steps) → divergence check
//   on them → CSV row → trajectory rows.
#include <chrono>
#include <string>
#include <utility>

#include "output/csv_writer.h"
#include "particles/divergence.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"

namespace cli {

struct RunOutputs {
  output::CsvWriter* csv = nullptr;         // rows of kDiagnosticsColumns
  output::CsvWriter* trajectory = nullptr;  // rows of kTrajectoryColumns
  long long every = 1;                 // trajectory rows every `every` steps (and at step 0)
  // Diagnostics, the divergence check and the CSV row every this many steps
  // (and at step 0): a divergence is found up to diagnosticsEvery − 1 steps late.
  long long diagnosticsEvery = 1;
};

class RunLoop {
 public:
  // sceneLength: L of the energy bound (runnerDivergenceLimits, sceneLength()).
  RunLoop(particles::ParticleSystem& system, particles::Integrator& integrator, double dt, RunOutputs outputs,
          double sceneLength);

  // Row 0, the initial state. Returns why the run cannot go on (a
  // non-finite diagnostic), empty when it can.
  std::string start();
  // One step and its rows. Returns the divergence reason (the step diverged
  // or failed, or a diagnostic is not finite; nothing is written then), empty
  // when the run goes on.
  std::string step();

  long long steps() const { return steps_; }  // steps completed
  // A notice for stderr, once, empty otherwise: the first step whose CG
  // passed its work bound and was solved directly.
  std::string takeNotice() { return std::exchange(notice_, {}); }
  // The last step() ran while a signal arrived: it was not counted or written.
  bool cancelledStep() const { return cancelledStep_; }
  // Wall time spent in ParticleSystem::step, output excluded.
  double simulatedSeconds() const { return std::chrono::duration<double>(simulated_).count(); }

 private:
  particles::ParticleSystem& system_;
  particles::Integrator& integrator_;
  double dt_;
  RunOutputs outputs_;
  particles::DivergenceLimits limits_;
  double initialEnergy_;
  long long steps_ = 0;
  bool cancelledStep_ = false;
  bool noticedFallback_ = false;
  std::string notice_;
  std::chrono::steady_clock::duration simulated_{};
};

}  // namespace cli

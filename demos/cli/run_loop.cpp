#include "cli/run_loop.h"

#include "cli/step_output.h"
#include "particles/cancel.h"

namespace cli {

RunLoop::RunLoop(particles::ParticleSystem& system, particles::Integrator& integrator, double dt, RunOutputs outputs,
                 double sceneLength)
    : system_(system),
      integrator_(integrator),
      dt_(dt),
      outputs_(outputs),
      limits_(runnerDivergenceLimits(system, sceneLength)),
      initialEnergy_(system.totalEnergy()) {}

std::string RunLoop::start() {
  const Diagnostics initial = measureDiagnostics(0, system_);
  if (std::string reason = nonFiniteDiagnostics(initial); !reason.empty()) return reason;
  if (outputs_.csv) writeDiagnostics(*outputs_.csv, initial, 0.0);
  if (outputs_.trajectory) writeTrajectory(*outputs_.trajectory, 0, system_);
  return {};
}

std::string RunLoop::step() {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  const particles::StepStats stats = system_.step(integrator_, dt_);
  const Clock::duration elapsed = Clock::now() - start;
  // A signal during the step may have cut its solves short (particles/cancel.h):
  // the step is not written, and the outputs end with the step before it.
  if (particles::cancelRequested()) {
    cancelledStep_ = true;
    return {};
  }
  simulated_ += elapsed;
  const long long step = steps_ + 1;
  if (stats.directFallbacks > 0 && !noticedFallback_) {
    noticedFallback_ = true;
    notice_ = particles::directFallbackMessage(static_cast<int>(system_.constraints().size()),
                                               system_.solver().settings) +
              ", from step " + std::to_string(step);
  }
  // Measured steps: the diagnostics once (each energy is a pass over the
  // forces), the divergence check on the same total energy, the CSV row.
  if (step % outputs_.diagnosticsEvery == 0) {
    const Diagnostics row = measureDiagnostics(step, system_);
    if (const particles::Divergence d =
            particles::checkDivergence(system_, limits_, initialEnergy_, stats, row.kinetic + row.potential))
      return d.message();
    if (std::string reason = nonFiniteDiagnostics(row); !reason.empty()) return reason;
    if (outputs_.csv)
      writeDiagnostics(*outputs_.csv, row, std::chrono::duration<double, std::micro>(elapsed).count());
  }
  if (outputs_.trajectory && step % outputs_.every == 0) writeTrajectory(*outputs_.trajectory, step, system_);
  steps_ = step;
  return {};
}

}  // namespace cli

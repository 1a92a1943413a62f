#include "cli/step_output.h"

#include <cmath>
#include <string>


namespace cli {

particles::DivergenceLimits runnerDivergenceLimits(particles::ParticleSystem& system, double sceneLength) {
  particles::DivergenceLimits limits;
  limits.maxRelativeConstraintError = particles::DivergenceLimits::off;
  limits.energyScale = particles::blowUpEnergyScale(system, sceneLength);
  limits.energyRiseFraction = kEnergyBoundFactor;
  limits.maxSolveResidual = kMaxSolveResidual;
  return limits;
}

double sceneLength(const scenes::Scene& scene) {
  Eigen::Vector2d lo = scene.viewMin.cwiseMin(scene.viewMax), hi = scene.viewMin.cwiseMax(scene.viewMax);
  const particles::ParticleSystem& s = *scene.system;
  for (int i = 0; i < s.size(); ++i) lo = lo.cwiseMin(s.position(i)), hi = hi.cwiseMax(s.position(i));
  return (hi - lo).norm();
}

Diagnostics measureDiagnostics(long long step, const particles::ParticleSystem& s) {
  Diagnostics d;
  d.step = step;
  d.time = s.time();
  d.kinetic = s.kineticEnergy();
  d.potential = s.potentialEnergy();
  d.constraintError = s.maxConstraintError();
  if (step > 0) d.stats = s.lastStepStats(), d.contacts = s.contactsLastStep();
  else d.stats.internalSteps = 0;  // no step taken yet
  return d;
}

std::string nonFiniteDiagnostics(const Diagnostics& d) {
  const std::pair<const char*, double> columns[] = {
      {"the time", d.time},
      {"the kinetic energy", d.kinetic},
      {"the potential energy", d.potential},
      {"the total energy", d.kinetic + d.potential},
      {"the constraint error", d.constraintError},
      {"the constraint solve's residual", d.stats.maxResidual},
  };
  for (const auto& [name, value] : columns)
    if (!std::isfinite(value)) return std::string(name) + " is not finite";
  return {};
}

void writeDiagnostics(output::CsvWriter& csv, const Diagnostics& d, double stepMicros) {
  const particles::StepStats& stats = d.stats;
  csv << d.step << d.time << d.kinetic << d.potential << d.kinetic + d.potential << d.constraintError
      << stats.cgIterations << stats.maxResidual << stats.solves << stats.forceEvaluations << stats.internalSteps
      << stepMicros << stats.threads << d.contacts << stats.sleeping;
  csv.endRow();
}

void writeTrajectory(output::CsvWriter& csv, long long step, const particles::ParticleSystem& s) {
  for (int i = 0; i < s.size(); ++i) {
    const Eigen::Vector2d x = s.position(i), v = s.velocity(i);
    csv << step << s.time() << i << x.x() << x.y() << v.x() << v.y();
    csv.endRow();
  }
}

}  // namespace cli

#include "cli/step_output.h"

#include <cmath>
#include <string>

#include "format_number.h"

namespace cli {

using scenes::formatNumber;

particles::DivergenceLimits runnerDivergenceLimits() {
  particles::DivergenceLimits limits;
  limits.maxRelativeConstraintError = particles::DivergenceLimits::off;
  return limits;
}

std::string nonFiniteDiagnostics(const particles::ParticleSystem& s) {
  const double kinetic = s.kineticEnergy(), potential = s.potentialEnergy();
  const std::pair<const char*, double> columns[] = {
      {"the time", s.time()},
      {"the kinetic energy", kinetic},
      {"the potential energy", potential},
      {"the total energy", kinetic + potential},
      {"the constraint error", s.maxConstraintError()},
      {"the constraint solve's residual", s.lastStepStats().maxResidual},
  };
  for (const auto& [name, value] : columns)
    if (!std::isfinite(value)) return std::string(name) + " is not finite";
  return {};
}

void writeDiagnostics(std::ostream& out, long long step, const particles::ParticleSystem& s, double stepMicros) {
  particles::StepStats stats = s.lastStepStats();
  if (step == 0) stats = particles::StepStats{}, stats.internalSteps = 0;  // no step taken yet
  const double kinetic = s.kineticEnergy(), potential = s.potentialEnergy();
  out << step << ',' << formatNumber(s.time()) << ',' << formatNumber(kinetic) << ',' << formatNumber(potential)
      << ',' << formatNumber(kinetic + potential) << ',' << formatNumber(s.maxConstraintError()) << ','
      << stats.cgIterations << ',' << formatNumber(stats.maxResidual) << ',' << stats.solves << ','
      << stats.forceEvaluations << ',' << stats.internalSteps << ',' << formatNumber(stepMicros) << '\n';
}

void writeTrajectory(std::ostream& out, long long step, const particles::ParticleSystem& s) {
  const std::string prefix = std::to_string(step) + ',' + formatNumber(s.time()) + ',';
  for (int i = 0; i < s.size(); ++i) {
    const Eigen::Vector2d x = s.position(i), v = s.velocity(i);
    out << prefix << i << ',' << formatNumber(x.x()) << ',' << formatNumber(x.y()) << ','
        << formatNumber(v.x()) << ',' << formatNumber(v.y()) << '\n';
  }
}

}  // namespace cli

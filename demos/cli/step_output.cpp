#include "cli/step_output.h"

#include <cmath>
#include <string>

#include "format_number.h"

namespace cli {

using scenes::formatNumber;

bool diverged(const particles::ParticleSystem& s) {
  return !std::isfinite(s.positions().squaredNorm()) || !std::isfinite(s.velocities().squaredNorm());
}

Diagnostics measure(const particles::ParticleSystem& s) {
  Diagnostics d;
  d.time = s.time();
  d.kinetic = s.kineticEnergy();
  d.potential = s.potentialEnergy();
  d.maxConstraintError = s.maxConstraintError();
  d.cgIterations = s.lastSolve().iterations;
  d.cgResidual = s.lastSolve().residual;
  return d;
}

std::string nonFinite(const Diagnostics& d) {
  const std::pair<const char*, double> values[] = {
      {"the time", d.time},
      {"the kinetic energy", d.kinetic},
      {"the potential energy", d.potential},
      {"the total energy", d.kinetic + d.potential},
      {"the constraint error", d.maxConstraintError},
      {"the constraint solve's residual (the solve for lambda failed)", d.cgResidual},
  };
  for (const auto& [name, value] : values)
    if (!std::isfinite(value)) return std::string(name) + " is not finite";
  return {};
}

void writeDiagnostics(std::ostream& out, long long step, const Diagnostics& d, double stepMicros) {
  out << step << ',' << formatNumber(d.time) << ',' << formatNumber(d.kinetic) << ',' << formatNumber(d.potential)
      << ',' << formatNumber(d.kinetic + d.potential) << ',' << formatNumber(d.maxConstraintError) << ','
      << d.cgIterations << ',' << formatNumber(d.cgResidual) << ',' << formatNumber(stepMicros) << '\n';
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

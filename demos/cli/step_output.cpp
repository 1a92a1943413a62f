#include "cli/step_output.h"

#include <cmath>
#include <string>

#include "format_number.h"

namespace cli {

using scenes::formatNumber;

bool diverged(const particles::ParticleSystem& s) {
  return !std::isfinite(s.positions().squaredNorm()) || !std::isfinite(s.velocities().squaredNorm());
}

void writeDiagnostics(std::ostream& out, long long step, const particles::ParticleSystem& s, double stepMicros) {
  const double kinetic = s.kineticEnergy(), potential = s.potentialEnergy();
  out << step << ',' << formatNumber(s.time()) << ',' << formatNumber(kinetic) << ',' << formatNumber(potential)
      << ',' << formatNumber(kinetic + potential) << ',' << formatNumber(s.maxConstraintError()) << ','
      << s.lastSolve().iterations << ',' << formatNumber(s.lastSolve().residual) << ','
      << formatNumber(stepMicros) << '\n';
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

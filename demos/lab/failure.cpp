#include "lab/failure.h"

#include <cmath>
#include <functional>
#include <queue>
#include <sstream>

#include "particles/constraints/circular_wire.h"
#include "particles/constraints/rod.h"
#include "particles/forces/gravity.h"

namespace lab {

using particles::ParticleSystem;

const char* failureName(Failure failure) { return particles::divergenceReasonName(failure); }

bool isBlowUp(Failure failure) {
  return failure == Failure::NonFinite || failure == Failure::StepFailed || failure == Failure::EnergyGrowth ||
         failure == Failure::OutOfBounds;
}

particles::DivergenceLimits divergenceLimits(const FailureCriterion& criterion, double energyScale) {
  particles::DivergenceLimits limits;
  limits.maxRelativeConstraintError = criterion.maxRelativeConstraintError;
  limits.energyRiseFraction = criterion.energyRiseFraction;
  limits.energyScale = energyScale;
  return limits;
}

double releasableEnergy(const ParticleSystem& system) {
  const int n = system.size();
  const particles::GravityForce* gravity = nullptr;
  for (const auto& force : system.forceObjects())
    if (auto* g = dynamic_cast<const particles::GravityForce*>(force.get())) gravity = g;

  const particles::Phase phase = system.phase();
  double elastic = system.potentialEnergy() - (gravity ? gravity->potential(phase) : 0.0);
  double energy = system.kineticEnergy() + std::max(0.0, elastic);

  const double g = gravity ? gravity->acceleration().norm() : 0.0;
  if (g > 0.0 && n > 0) {
    const Eigen::Vector2d up = -gravity->acceleration() / g;
    Eigen::Vector2d lo = system.position(0), hi = lo;
    for (int i = 0; i < n; ++i) lo = lo.cwiseMin(system.position(i)), hi = hi.cwiseMax(system.position(i));
    const double diagonal = (hi - lo).norm();

    // c_i = min over holders a of (d_ai − low_a): particle i hangs no lower than −c_i.
    std::vector<std::vector<std::pair<int, double>>> rods(n);
    std::vector<double> cost(n, std::numeric_limits<double>::infinity());
    for (int i = 0; i < n; ++i)
      if (system.pinned(i)) cost[i] = -up.dot(system.position(i));
    for (const auto& c : system.constraints()) {
      if (auto* rod = dynamic_cast<const particles::RodConstraint*>(c.get())) {
        const int a = rod->particles()[0], b = rod->particles()[1];
        rods[a].push_back({b, rod->length()});
        rods[b].push_back({a, rod->length()});
      } else if (auto* wire = dynamic_cast<const particles::CircularWireConstraint*>(c.get())) {
        const int p = wire->particles()[0];
        cost[p] = std::min(cost[p], -(up.dot(wire->centre()) - wire->radius()));
      }
    }
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (int i = 0; i < n; ++i)
      if (std::isfinite(cost[i])) queue.push({cost[i], i});
    while (!queue.empty()) {
      const auto [c, i] = queue.top();
      queue.pop();
      if (c > cost[i]) continue;
      for (const auto& [j, length] : rods[i])
        if (c + length < cost[j]) queue.push({cost[j] = c + length, j});
    }
    for (int i = 0; i < n; ++i) {
      if (system.pinned(i)) continue;
      const double drop = std::isfinite(cost[i]) ? std::max(0.0, up.dot(system.position(i)) + cost[i]) : diagonal;
      energy += system.masses()[i] * g * drop;
    }
  }
  return std::max(energy, 1e-12 * std::abs(system.totalEnergy()) + 1e-300);
}

std::string describe(const FailureCriterion& criterion) {
  std::ostringstream s;
  s << "failure criterion: a run fails at the first step with a non-finite state or a failed step, "
    << "or max |C|/r > " << criterion.maxRelativeConstraintError << " (constraint), "
    << "or E(t) - E(0) > " << criterion.energyRiseFraction
    << " x E_s (energy; E_s = the scene's releasable energy, for the test chain g m L cl(cl-1)/2)";
  return s.str();
}

Failure checkFailure(const ParticleSystem& system, const particles::DivergenceLimits& limits, double energyStart,
                     const particles::StepStats& lastStep) {
  return particles::checkDivergence(system, limits, energyStart, lastStep).reason;
}

}  // namespace lab

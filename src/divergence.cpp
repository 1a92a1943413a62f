#include "particles/divergence.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "particles/check.h"
#include "particles/particle_system.h"

namespace particles {

namespace {

struct ReasonInfo {
  DivergenceReason reason;
  const char* name;
};

constexpr ReasonInfo kReasons[] = {
    {DivergenceReason::None, "none"},
    {DivergenceReason::NonFinite, "non-finite"},
    {DivergenceReason::ConstraintViolation, "constraint"},
    {DivergenceReason::EnergyGrowth, "energy"},
    {DivergenceReason::StepFailed, "step-failed"},
    {DivergenceReason::SolveFailed, "solve-failed"},
    {DivergenceReason::OutOfBounds, "out-of-bounds"},
};

void requireLimit(const char* name, double value) {
  if (!(value > 0.0))  // +inf (the test off) is allowed, NaN is not
    throw std::invalid_argument(std::string("divergence limit ") + name + " must be > 0, got " +
                                formatValue(value));
}

}  // namespace

const char* divergenceReasonName(DivergenceReason reason) {
  for (const ReasonInfo& info : kReasons)
    if (info.reason == reason) return info.name;
  return "unknown";
}

void DivergenceLimits::validate() const {
  requireLimit("maxRelativeConstraintError", maxRelativeConstraintError);
  requireLimit("maxConstraintError", maxConstraintError);
  requireLimit("energyScale", energyScale);
  requireLimit("energyRiseFraction", energyRiseFraction);
  requireLimit("maxCoordinate", maxCoordinate);
  requireLimit("maxSolveResidual", maxSolveResidual);
}

std::string Divergence::message() const {
  switch (reason) {
    case DivergenceReason::None: return "no divergence";
    case DivergenceReason::NonFinite:
      return "the positions, velocities or energy are no longer finite (|q|^2, |v|^2 or E overflows)";
    case DivergenceReason::StepFailed: return std::string("the step failed: ") + stepFailureName(failure);
    case DivergenceReason::SolveFailed:
      return "a constraint solve left a relative residual of " + formatValue(value) + ", above the limit " +
             formatValue(limit) + " (its multipliers are no solution)";
    case DivergenceReason::ConstraintViolation:
      return relative ? "the relative constraint error max |C|/r reached " + formatValue(value) + ", above the limit " +
                            formatValue(limit) + " (r: a rod's length, a wire's radius)"
                      : "the constraint error max |C| reached " + formatValue(value) + " (world units), above the limit " +
                            formatValue(limit);
    case DivergenceReason::EnergyGrowth:
      return "the energy rose by " + formatValue(value) + ", more than the limit " + formatValue(limit);
    case DivergenceReason::OutOfBounds:
      return "a coordinate reached " + formatValue(value) + ", beyond the limit " + formatValue(limit);
  }
  return "unknown divergence";
}

double blowUpEnergyScale(ParticleSystem& system, double length) {
  requireNonNegative("blow-up length", length);
  const Phase s = system.phase();
  double potentials = 0.0;
  for (const auto& force : system.forceObjects())
    if (force->hasPotential()) potentials += std::abs(force->potential(s));
  Eigen::VectorXd f = Eigen::VectorXd::Zero(system.positions().size());
  system.appliedForces(system.positions(), system.velocities(), f);
  double forces = 0.0;
  for (int i = 0; i < system.size(); ++i)
    if (!system.pinned(i)) forces += f.segment<2>(2 * i).norm();
  const double scale = std::abs(system.totalEnergy()) + system.kineticEnergy() + potentials + length * forces;
  return std::max(scale, 1e-300);
}

Divergence checkDivergence(const ParticleSystem& system, const DivergenceLimits& limits,
                           double initialEnergy, const StepStats& lastStep) {
  return checkDivergence(system, limits, initialEnergy, lastStep, system.totalEnergy());
}

Divergence checkDivergence(const ParticleSystem& system, const DivergenceLimits& limits,
                           double initialEnergy, const StepStats& lastStep, double totalEnergy) {
  Divergence d;
  auto fail = [&](DivergenceReason reason, double value, double limit) {
    d.reason = reason;
    d.value = value;
    d.limit = limit;
    return d;
  };
  // Squared norms overflow to inf long before the coordinates do.
  const double q2 = system.positions().squaredNorm(), v2 = system.velocities().squaredNorm();
  if (!std::isfinite(q2) || !std::isfinite(v2)) return fail(DivergenceReason::NonFinite, q2 + v2, 0.0);
  const double energy = totalEnergy;
  if (!std::isfinite(energy)) return fail(DivergenceReason::NonFinite, energy, 0.0);
  if (lastStep.failure != StepFailure::None) {
    d.failure = lastStep.failure;
    return fail(DivergenceReason::StepFailed, 0.0, 0.0);
  }
  if (lastStep.solves > 0 && !(lastStep.maxResidual <= limits.maxSolveResidual))
    return fail(DivergenceReason::SolveFailed, lastStep.maxResidual, limits.maxSolveResidual);
  if (!system.constraints().empty()) {
    const double relative = system.maxRelativeConstraintError();
    if (!(relative <= limits.maxRelativeConstraintError)) {
      d.relative = true;
      return fail(DivergenceReason::ConstraintViolation, relative, limits.maxRelativeConstraintError);
    }
    if (std::isfinite(limits.maxConstraintError)) {
      const double absolute = system.maxConstraintError();
      if (!(absolute <= limits.maxConstraintError))
        return fail(DivergenceReason::ConstraintViolation, absolute, limits.maxConstraintError);
    }
  }
  if (std::isfinite(limits.energyScale)) {
    const double rise = energy - initialEnergy, allowed = limits.energyRiseFraction * limits.energyScale;
    if (rise > allowed) return fail(DivergenceReason::EnergyGrowth, rise, allowed);
  }
  if (std::isfinite(limits.maxCoordinate) && system.positions().size() > 0) {
    const double far = system.positions().cwiseAbs().maxCoeff();
    if (far > limits.maxCoordinate) return fail(DivergenceReason::OutOfBounds, far, limits.maxCoordinate);
  }
  return d;
}

}  // namespace particles

#pragma once
// When a simulation counts as diverged: one definition for the runner, the
// laboratory and the demo, each passing its own thresholds.
//
// A state diverges at the first step where, in this order,
//  - a position, a velocity or the total energy is not finite (NonFinite; also
//    |q|² or |q̇|² overflowing, which an exploding state reaches many steps
//    before inf appears in q itself);
//  - the step failed (StepFailed: a solve gave non-finite multipliers, or an
//    adaptive scheme hit its step floor or its work cap);
//  - a constraint solve of the step left a relative residual |r|/|b| above
//    maxSolveResidual (SolveFailed; off by default): its multipliers are not
//    a solution (an iterative solve that cannot converge on a contradictory
//    constraint set, where the damped direct solve finds the least-squares one);
//  - max |C|/r > maxRelativeConstraintError over the constraints with a length
//    scale r, or max |C| > maxConstraintError in world units over all of them
//    (ConstraintViolation);
//  - E − E₀ > energyRiseFraction · energyScale (EnergyGrowth; off while
//    energyScale is infinite): the laboratory's E_s with a fraction of 0.1
//    (lab/failure.h), the runner's blow-up bound blowUpEnergyScale() with a
//    factor of 100 (cli/step_output.h);
//  - some coordinate |q_i| > maxCoordinate, world units (OutOfBounds).
// The thresholds default to the laboratory's except those that need a scale
// of the scene (energyScale, maxConstraintError, maxCoordinate): the tool
// supplies them, or leaves the test off.
#include <limits>
#include <string>

#include "particles/step_stats.h"

namespace particles {

class ParticleSystem;

enum class DivergenceReason { None, NonFinite, ConstraintViolation, EnergyGrowth, StepFailed, SolveFailed, OutOfBounds };

// "none", "non-finite", "constraint", "energy", "step-failed", "solve-failed", "out-of-bounds".
const char* divergenceReasonName(DivergenceReason reason);

struct DivergenceLimits {
  static constexpr double off = std::numeric_limits<double>::infinity();
  double maxRelativeConstraintError = 0.1;  // max |C|/r, dimensionless
  double maxConstraintError = off;          // max |C|, world units
  double energyScale = off;                 // energy the scene can release, J; tool-supplied
  double energyRiseFraction = 0.1;          // fail when E − E₀ > fraction · energyScale
  double maxCoordinate = off;               // |q_i|, world units
  double maxSolveResidual = off;            // a solve's relative residual |r|/|b|

  void validate() const;  // throws naming the bad field (each must be > 0; NaN refused)
};

struct Divergence {
  DivergenceReason reason = DivergenceReason::None;
  double value = 0.0, limit = 0.0;  // the measured quantity and the threshold it crossed
  StepFailure failure = StepFailure::None;  // for StepFailed: which
  bool relative = false;  // for ConstraintViolation: max |C|/r (true) or max |C| in world units

  explicit operator bool() const { return reason != DivergenceReason::None; }
  // One line, e.g. "max |C|/r = 0.31 exceeds 0.1" or "the step failed: work-cap".
  std::string message() const;
};

// The energy scale of a scene for a blow-up bound, from its state at the
// start and a length L of the scene (the runner's: the diagonal of the box
// around the scene's view and its initial positions):
//   E_ref = |E(0)| + K(0) + Σ_f |V_f(0)| + L · Σ_i |F_i(0)|,
// K the kinetic energy, V_f each force's potential, F_i the applied force on
// moving particle i at the start (m g under gravity; a spring at rest adds
// none). The last term is the work the starting forces could do across the
// scene; with the first it keeps E_ref away from zero for a scene at rest
// whose energies happen to vanish (one particle at rest on a floor at y = 0).
// A scheme that stays stable changes the energy by a modest multiple of it
// at most; an unstable one multiplies the energy step after step (explicit
// Euler on a spring by 1 + ω²h² per step) and passes any multiple long
// before its state overflows. Only a rise is judged: damping, drag and
// inelastic contacts take energy out without bound over a long fall.
// At least 1e-300.
double blowUpEnergyScale(ParticleSystem& system, double length);

// Checks the system after a step. initialEnergy is E₀, the total energy the
// run started from; lastStep the statistics of the step just taken.
Divergence checkDivergence(const ParticleSystem& system, const DivergenceLimits& limits,
                           double initialEnergy, const StepStats& lastStep);
// The same with the system's total energy already measured (a runner that
// has just computed it for its diagnostics does not pay for it twice).
Divergence checkDivergence(const ParticleSystem& system, const DivergenceLimits& limits,
                           double initialEnergy, const StepStats& lastStep, double totalEnergy);

}  // namespace particles

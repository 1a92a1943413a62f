#pragma once
// The laboratory's failure criterion, defined once and used by every
// experiment and quoted in the report. A run fails at the first step where
//   - a position or velocity is not finite                       (non-finite),
//   - the step itself throws (a solve that cannot proceed)        (step-failed),
//   - max over constraints of |C|/r exceeds maxRelativeConstraintError,
//     with |C| in length units and r the constraint's length       (constraint),
//   - E(t) − E(0) exceeds energyRiseFraction × E_s, E_s the scene's
//     releasable energy (releasableEnergy below)                  (energy).
// Non-finite, step-failed and energy growth are a blow-up of the integration;
// a constraint violation with bounded energy is the scene stretching its rods
// (a whip, a starved solver) and is reported apart from it.
#include <string>

#include "particles/divergence.h"
#include "particles/particle_system.h"
#include "particles/step_stats.h"

namespace lab {

struct FailureCriterion {
  double maxRelativeConstraintError = 0.1;  // max |C|/r, dimensionless
  double energyRiseFraction = 0.1;          // of the releasable energy E_s, dimensionless
};

// The engine's divergence reasons (particles/divergence.h), which do the checking.
using Failure = particles::DivergenceReason;

// "none", "non-finite", "step-failed", "constraint", "energy", "out-of-bounds": the CSV spelling.
const char* failureName(Failure failure);

// Non-finite state, a failed step or energy growth: the integration went unstable.
bool isBlowUp(Failure failure);

// The engine's limits for this criterion and a scene of releasable energy E_s.
particles::DivergenceLimits divergenceLimits(const FailureCriterion& criterion, double energyScale);

// E_s, the energy the scene can release, from its initial state:
//   E_s = K(0) + V_elastic(0) + Σ_i m_i |g| δ_i
// K the kinetic energy, V_elastic every potential but gravity's (springs), and
// δ_i ≥ 0 the largest drop of moving particle i below its start: hanging
// straight down from its nearest holder, δ_i = max(0, h_i − (h_a − d_i)) with
// h the height along −g, a a pinned particle reached over rods (d_i the summed
// rod lengths of the shortest such path) or the lowest point of a circular
// wire the particle or its path rides on. A particle held by nothing (a free
// body) can fall without limit; it gets δ_i = D, the diagonal of the scene's
// initial bounding box. For the test chain (cl particles, rods of length L,
// mass m, start horizontal at the pin) this is g·m·L·cl(cl−1)/2, the potential
// drop to hanging straight. Never zero: at least 1e-12 |E(0)| + 1e-300.
double releasableEnergy(const particles::ParticleSystem& system);

// The criterion as one line, printed by every experiment and quoted in the report.
std::string describe(const FailureCriterion& criterion);

// Checks the state after a step (particles::checkDivergence); energyStart = E(0).
Failure checkFailure(const particles::ParticleSystem& system, const particles::DivergenceLimits& limits,
                     double energyStart, const particles::StepStats& lastStep);

}  // namespace lab

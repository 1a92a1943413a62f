#include "particles/integrator.h"

#include <stdexcept>

#include "particles/check.h"
#include "integrators/dopri5.h"
#include "particles/particle_system.h"
#include "integrators/explicit_euler.h"
#include "integrators/implicit_euler.h"
#include "integrators/midpoint.h"
#include "integrators/rattle.h"
#include "integrators/rk4.h"
#include "integrators/symplectic_euler.h"
#include "integrators/verlet.h"
#include "integrators/xpbd.h"

namespace particles {

namespace {
template <class T>
std::unique_ptr<Integrator> make() {
  return std::make_unique<T>();
}

// IntegratorInfo's flags (usesTolerance, usesSubsteps, implicitForces), named
// where the table sets them.
constexpr bool kReadsTolerance = true, kNoTolerance = false;
constexpr bool kReadsSubsteps = true, kNoSubsteps = false;
constexpr bool kImplicitForces = true;
}  // namespace

const std::vector<IntegratorInfo>& integratorTable() {
  static const std::vector<IntegratorInfo> table = {
      {"euler", "explicit Euler: x and v both from the old state",
       "gains energy every oscillation, stable only while damping outruns it (omega dt < 2 zeta); 1 force evaluation a step", 1, make<ExplicitEulerIntegrator>},
      {"symplectic-euler", "symplectic Euler: v first, then x with the new v (the seed's \"Euler\")",
       "energy stays bounded for omega dt < 2; 1 force evaluation a step", 1,
       make<SymplecticEulerIntegrator>},
      {"midpoint", "explicit midpoint (RK2)",
       "gains energy by (omega dt)^4/4 a step: fine for short runs at small omega dt; 2 force evaluations a step", 2, make<MidpointIntegrator>},
      {"rk4", "classic fourth-order Runge-Kutta",
       "loses a little energy, stable for omega dt < 2.8; 4 force evaluations a step", 4, make<Rk4Integrator>},
      {"verlet", "velocity Verlet, velocity-dependent forces at a predicted velocity",
       "symplectic: energy bounded for omega dt < 2; 1 force evaluation a step", 2,
       make<VerletIntegrator>},
      {"rattle", "RATTLE: velocity Verlet with positions and velocities projected onto the constraints; no drift",
       "symplectic, constraints held exactly: omega dt < 2; 1 force evaluation and two projections a step", 2,
       make<RattleIntegrator>},
      {"implicit-euler", "backward Euler, constraints in the solve, Newton passes to convergence; never gains energy",
       "stable at any dt, but damps the motion, more at larger dt; a linear solve per Newton pass", 1,
       make<ImplicitEulerIntegrator>, kNoTolerance, kNoSubsteps, kImplicitForces},
      {"dopri5", "Dormand-Prince 5(4), FSAL, PI step control: internal step chosen to meet --tolerance",
       "accurate to its tolerance, but a stiff scene makes it take many small internal steps; 6 evaluations each", 5,
       make<Dopri5Integrator>, kReadsTolerance},
      {"xpbd", "XPBD: --substeps substeps of --iterations constraint passes, springs as compliance (--lines: hanging lines solved directly)",
       "stable at any dt on springs and constraints, a little damping; one pass over every spring a substep", 1,
       make<XpbdIntegrator>, kNoTolerance, kReadsSubsteps, kImplicitForces},
  };
  return table;
}

Eigen::VectorXd& Integrator::positionsOf(ParticleSystem& system) { return system.x_; }
Eigen::VectorXd& Integrator::velocitiesOf(ParticleSystem& system) { return system.v_; }

void IntegratorSettings::validate() const {
  dopri5.validate();
  xpbd.validate();
  implicitEuler.validate();
}

void Dopri5Settings::validate() const {
  requirePositive("integrator tolerance", tolerance);
  if (tolerance < minTolerance)
    throw std::invalid_argument("integrator tolerance must be >= " + formatValue(minTolerance) +
                                " (below it double precision cannot meet it), got " + formatValue(tolerance));
  requireInRange("integrator minStepFraction", minStepFraction, 1e-15, 1.0);
  if (maxStepsPerCall < 1)
    throw std::invalid_argument("integrator maxStepsPerCall must be >= 1, got " + std::to_string(maxStepsPerCall));
}

void XpbdSettings::validate() const {
  requireInRange("integrator substeps", substeps, substepRange.min, substepRange.max);
  requireInRange("integrator iterations", iterations, iterationRange.min, iterationRange.max);
}

const IntegratorInfo* findIntegrator(const std::string& name) {
  for (const IntegratorInfo& info : integratorTable())
    if (name == info.name) return &info;
  return nullptr;
}

std::string integratorNames() {
  std::string names;
  for (const IntegratorInfo& info : integratorTable()) {
    names += names.empty() ? "" : ", ";
    names += info.name;
  }
  return names;
}

const IntegratorInfo& requireIntegrator(const std::string& name) {
  if (const IntegratorInfo* info = findIntegrator(name)) return *info;
  throw std::invalid_argument("unknown integrator '" + name + "' (valid: " + integratorNames() + ")");
}

std::unique_ptr<Integrator> makeIntegrator(const std::string& name,
                                           const IntegratorSettings& settings) {
  std::unique_ptr<Integrator> integrator = requireIntegrator(name).make();
  integrator->configure(settings);
  return integrator;
}

}  // namespace particles

#pragma once
// The Integrator interface and the table of integrators selectable by name.
#include <memory>
#include <string>
#include <vector>

#include "particles/drift_correction.h"
#include "particles/integrators/implicit_euler_settings.h"
#include "particles/step_stats.h"

namespace particles {

class ParticleSystem;

// Settings an integrator may use, set by name from the command line and the
// panel. Fixed-step schemes ignore them; one struct keeps makeIntegrator's
// signature the same for every scheme.
struct IntegratorSettings {
  // Adaptive schemes (dopri5): local error allowed per internal
  // step, mixed absolute and relative — error_i against tolerance·(1 + |y_i|)
  // for every component of y = (x, v); each scheme's header gives its norm.
  // 2e-5, the tightest value of the 1–2–5 series at which dopri5 on the
  // 80-rod chain at dt 0.01 keeps within the engine's cost target of 1.6 RK4
  // steps: 29 internal steps and 1 rejected per 30 output steps, 6.0
  // evaluations per output step against RK4's 4, 1.54 RK4 steps in
  // instructions (tests/bench/bench_step.cpp, scripts/callgrind-step.sh); it
  // ends 0.35 s 4.8× closer to a tight reference than RK4 at that dt does
  // (test Dopri5.TheDefaultToleranceBeatsRk4AtTheScenesStep prints both
  // errors). At 1e-5 it took 33 internal steps (6.6 evaluations, 1.70 RK4
  // steps) for 8.6× RK4's accuracy. The global error follows the tolerance
  // (report, §3.4 "Accuracy: work against precision").
  double tolerance = 2e-5;
  // Below this the error estimate is dominated by rounding (the stages differ
  // by a few ulps of y): a smaller tolerance is refused rather than chased.
  static constexpr double minTolerance = 1e-13;
  // Floor of the internal step, as a fraction of the interval dt of one call:
  // a step the controller would shrink below it fails the call with
  // StepFailure::StepBelowFloor instead of being accepted anyway.
  double minStepFraction = 1e-9;
  // Work cap: internal steps (accepted and rejected) one call may attempt
  // before it fails with StepFailure::WorkCapReached.
  long maxStepsPerCall = 100000;
  // xpbd: a step of dt is `substeps` substeps of h = dt/substeps, each with
  // `iterations` Gauss–Seidel passes over the constraints (both ≥ 1). Macklin
  // et al. 2019 favour many substeps of one pass; the defaults are measured by
  // `particle-lab small-steps` (report, "Small steps").
  int substeps = 20;
  int iterations = 1;
  // implicit-euler: its Newton passes, constraint coupling and linear solver.
  ImplicitEulerSettings implicitEuler;

  void validate() const;  // throws naming the bad field
};

class Integrator {
 public:
  virtual ~Integrator() = default;

  virtual const char* name() const = 0;

  // Advances the system's positions and velocities by dt, evaluating
  // accelerations through ParticleSystem::acceleration (forces plus constraint
  // forces). Collisions and the clock are the caller's (ParticleSystem::step).
  // An adaptive scheme may take several internal steps to cover dt.
  // Returns what the step did: the evaluations and solves made through
  // ParticleSystem::acceleration (ParticleSystem::takeEvaluationStats) plus the
  // scheme's own solves, internal and rejected steps, and any failure.
  virtual StepStats step(ParticleSystem& system, double dt) = 0;

  // True for a scheme that resolves contacts inside its own substeps, calling
  // ParticleSystem::collideOver after each; the step's collision pass over the
  // whole step (ParticleSystem::step) is then skipped.
  virtual bool collidesInSubsteps() const { return false; }

  // The post-step contact phase resolves the particles that touch a collider
  // together with the constraints that hold them (src/collision/coupled_contacts.h).
  // How that coupled solve corrects the constraints' drift (src/collision/coupled_contacts.h):
  // DriftCorrection::Shake for a scheme whose step ends with x = x0 + dt v.
  virtual DriftCorrection driftCorrection() const { return DriftCorrection::AtEnd; }

  // The step over which this scheme applies a stiff force on one particle
  // (the mouse joint) explicitly, which bounds how stiff that force may be
  // (grab.h): dt for the explicit schemes; 0 for a scheme that takes it
  // implicitly (implicit Euler through its Jacobians, xpbd in position form).
  virtual double explicitForceStep(double dt) const { return dt; }

  // The internal step size last used; equals dt for fixed-step schemes.
  virtual double lastInternalStep() const { return lastStep_; }

  // Takes the settings this scheme uses (validated first); others are ignored.
  virtual void configure(const IntegratorSettings& settings) { settings.validate(); }

 protected:
  double lastStep_ = 0.0;
};

struct IntegratorInfo {
  const char* name;     // command-line name
  const char* summary;  // one line for `list` and the help overlay
  int order;            // global order of accuracy on smooth problems
  std::unique_ptr<Integrator> (*make)();
  bool usesTolerance = false;  // reads IntegratorSettings (tolerance, step floor, work cap)
  bool usesSubsteps = false;   // reads IntegratorSettings::substeps and ::iterations
  // Part of the laboratory's default sweeps over long chains and large
  // scenes (stability, timing, cost, extremes); a scheme left out is run there
  // only when named (--integrators), and the long-time and accuracy experiments
  // on small scenes run every scheme.
  bool inLabSweeps = true;
};

// Every integrator, in the order the demo cycles through them.
const std::vector<IntegratorInfo>& integratorTable();

// The table's entry named `name`, or nullptr: the one lookup by name that the
// runner, the demo, the laboratory and the scene reader share.
const IntegratorInfo* findIntegrator(const std::string& name);

// The table's entry named `name`; throws std::invalid_argument
// "unknown integrator 'NAME' (valid: …)" for an unknown one.
const IntegratorInfo& requireIntegrator(const std::string& name);

// Every integrator's name, in table order, as "euler, symplectic-euler, …".
std::string integratorNames();

// The entry named `name` made and configured with the given settings; throws
// as requireIntegrator for an unknown name.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name,
                                           const IntegratorSettings& settings = {});

}  // namespace particles

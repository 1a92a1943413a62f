#pragma once
// The Integrator interface, the settings a scheme may take, and the table of
// integrators selectable by name (the schemes themselves: src/integrators/).
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "particles/step_stats.h"

namespace particles {

class ParticleSystem;

// Dormand–Prince 5(4) (src/integrators/dopri5.h).
struct Dopri5Settings {
  // Local error allowed per internal step, mixed absolute and relative —
  // error_i against tolerance·(1 + |y_i|) for every component of y = (x, v);
  // dopri5.h gives the norm.
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
  // false: every call is one step of dt, no error control (order tests).
  bool adaptive = true;

  void validate() const;  // throws naming the bad field
};

// Implicit Euler (src/integrators/implicit_euler.h).
enum class ImplicitLinearSolver {
  Direct,             // LDLᵀ of the Newton passes' KKT matrix
  ConjugateGradient,  // Jacobi-preconditioned CG on A; constrained systems use Direct
};

struct ImplicitEulerSettings {
  // true: constraints inside the solve (the coupled scheme of src/integrators/implicit_euler.h). false: the constraint forces of
  // the explicit solve (ConstraintSolver, k_s/k_d feedback) at the start state,
  // held fixed through the step — the lagged scheme, kept for comparison.
  bool coupledConstraints = true;
  double stabilization = 1.0;          // β ∈ [0, 1]: fraction of C(x₀) removed in one step
  int constraintPasses = 20;           // most Newton solves per step (≥ 1)
  double constraintTolerance = 1e-10;  // relative residuals that end the passes (the stopping test)
  // Add G, the constraints' geometric stiffness (Tournier et al.
  // 2015). Without it the passes are Gauss–Newton and stall or diverge on a
  // long chain, whose tension h²|λ| ∇²C outweighs M.
  bool geometricStiffness = true;
  double compliance = 1e-10;           // ε, relative to diag(J W Jᵀ)
  ImplicitLinearSolver solver = ImplicitLinearSolver::ConjugateGradient;  // measured: tests/bench/bench_solvers.cpp
  double cgTolerance = 1e-6;           // relative residual of the CG solves
  int cgMaxIterations = 1000;

  void validate() const;  // throws naming the bad field
};

// The accepted range of an integer setting, declared once beside it: the
// engine validates by it, and the command line (its check and its help), the
// scene file's reader and the panel read it.
struct IntRange {
  int min, max;
};

// XPBD (src/integrators/xpbd.h).
struct XpbdSettings {
  // A step of dt is `substeps` substeps of h = dt/substeps, each with
  // `iterations` Gauss–Seidel passes over the constraints. Macklin et al.
  // 2019 favour many substeps of one pass; the defaults are measured by
  // `particle-lab small-steps` (report, "Small steps").
  int substeps = 20;
  int iterations = 1;
  // Upper bounds keep a typo from turning one step into hours of work.
  static constexpr IntRange substepRange{1, 100000};
  static constexpr IntRange iterationRange{1, 10000};
  // Solve each straight line of springs hanging from a held particle
  // directly, before each pass's Gauss–Seidel sweep (src/xpbd/hanging_lines.h):
  // a hanging cloth or strand then holds its length with a few substeps.
  bool lines = false;

  void validate() const;  // throws naming the bad field
};

// Settings an integrator may use, set by name from the command line and the
// panel: one struct per scheme that has any. Fixed-step schemes ignore them;
// one struct of them keeps makeIntegrator's signature the same for every scheme.
struct IntegratorSettings {
  Dopri5Settings dopri5;                // the adaptive scheme's tolerance, step floor and work cap
  XpbdSettings xpbd;                    // substeps and constraint passes
  ImplicitEulerSettings implicitEuler;  // Newton passes, constraint coupling and linear solver

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

  // The internal step size last used; equals dt for fixed-step schemes.
  virtual double lastInternalStep() const { return lastStep_; }

  // Takes the settings this scheme uses (validated first); others are ignored.
  virtual void configure(const IntegratorSettings& settings) { settings.validate(); }

 protected:
  // The state a scheme advances in place; the system's own accessors are
  // read-only (ParticleSystem::setPositions for everything else).
  static Eigen::VectorXd& positionsOf(ParticleSystem& system);
  static Eigen::VectorXd& velocitiesOf(ParticleSystem& system);

  double lastStep_ = 0.0;
};

struct IntegratorInfo {
  const char* name;     // command-line name
  const char* summary;  // one line for `list` and the help overlay
  // How it behaves, in one phrase for a user who switches to it: stability
  // (omega the fastest frequency, zeta its damping ratio: ASCII, as the
  // demo's font draws it) and cost.
  const char* behaviour;
  int order;            // global order of accuracy on smooth problems
  std::unique_ptr<Integrator> (*make)();
  bool usesTolerance = false;  // reads IntegratorSettings::dopri5 (tolerance, step floor, work cap)
  bool usesSubsteps = false;   // reads IntegratorSettings::xpbd (substeps, iterations)
  // Takes stiff forces implicitly (implicit Euler through its Jacobians, xpbd
  // in position form): no step bounds how stiff a force may be (grab.h).
  bool implicitForces = false;
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

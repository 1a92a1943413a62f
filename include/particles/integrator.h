#pragma once
// The Integrator interface and the table of integrators selectable by name.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "particles/integrators/dopri5_settings.h"
#include "particles/integrators/implicit_euler_settings.h"
#include "particles/integrators/xpbd_settings.h"
#include "particles/step_stats.h"

namespace particles {

class ParticleSystem;

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

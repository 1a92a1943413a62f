#pragma once
// The Integrator interface and the table of integrators selectable by name.
#include <memory>
#include <string>
#include <vector>

namespace particles {

class ParticleSystem;

class Integrator {
 public:
  virtual ~Integrator() = default;

  virtual const char* name() const = 0;

  // Advances the system's positions and velocities by dt, evaluating
  // accelerations through ParticleSystem::acceleration (forces plus constraint
  // forces). Collisions and the clock are the caller's (ParticleSystem::step).
  // An adaptive scheme may take several internal steps to cover dt.
  virtual void step(ParticleSystem& system, double dt) = 0;

  // The internal step size last used; equals dt for fixed-step schemes.
  virtual double lastInternalStep() const { return lastStep_; }

 protected:
  double lastStep_ = 0.0;
};

struct IntegratorInfo {
  const char* name;     // command-line name
  const char* summary;  // one line for `list` and the help overlay
  int order;            // global order of accuracy on smooth problems
  std::unique_ptr<Integrator> (*make)();
};

// Every integrator, in the order the demo cycles through them.
const std::vector<IntegratorInfo>& integratorTable();

// Throws std::invalid_argument listing the valid names for an unknown one.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name);

}  // namespace particles

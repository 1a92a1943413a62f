#include "step_continuation.h"

#include "particles/particle_system.h"

namespace particles {

bool StepContinuation::matches(const ParticleSystem& system) const {
  return kept_ && stamp_ == system.structureStamp() && !system.hasTimeDependentForces() &&
         x_.size() == system.positions().size() && x_ == system.positions() && v_ == system.velocities();
}

void StepContinuation::keep(const ParticleSystem& system) {
  x_ = system.positions();
  v_ = system.velocities();
  stamp_ = system.structureStamp();
  kept_ = true;
}

}  // namespace particles

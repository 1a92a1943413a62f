#include "integrators/verlet.h"

#include "particles/particle_system.h"

namespace particles {

StepStats VerletIntegrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = positionsOf(system);
  Eigen::VectorXd& v = velocitiesOf(system);
  // The cached acceleration is valid only for exactly the system it was left at.
  if (!continuation_.matches(system)) system.acceleration(x, v, a0_);

  x += dt * v + (0.5 * dt * dt) * a0_;
  vPredicted_ = v + dt * a0_;
  system.acceleration(x, vPredicted_, a1_);
  v += (0.5 * dt) * (a0_ + a1_);

  a0_.swap(a1_);
  continuation_.keep(system);
  lastStep_ = dt;
  return system.takeEvaluationStats();
}

}  // namespace particles

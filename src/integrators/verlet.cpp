#include "particles/integrators/verlet.h"

#include "particles/particle_system.h"

namespace particles {

StepStats VerletIntegrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = system.positions();
  Eigen::VectorXd& v = system.velocities();
  // The cached acceleration is valid only for exactly the state it was left at.
  const bool reuse = cached_ && xCached_.size() == x.size() && xCached_ == x && vCached_ == v;
  if (!reuse) system.acceleration(x, v, a0_);

  x += dt * v + (0.5 * dt * dt) * a0_;
  vPredicted_ = v + dt * a0_;
  system.acceleration(x, vPredicted_, a1_);
  v += (0.5 * dt) * (a0_ + a1_);

  a0_.swap(a1_);
  xCached_ = x;
  vCached_ = v;
  cached_ = true;
  lastStep_ = dt;
  return system.takeEvaluationStats();
}

}  // namespace particles

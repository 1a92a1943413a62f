#include "integrators/explicit_euler.h"

#include "particles/particle_system.h"

namespace particles {

StepStats ExplicitEulerIntegrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = positionsOf(system);
  Eigen::VectorXd& v = velocitiesOf(system);
  system.acceleration(x, v, a_);
  x += dt * v;
  v += dt * a_;
  lastStep_ = dt;
  return system.takeEvaluationStats();
}

}  // namespace particles

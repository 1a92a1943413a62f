#include "integrators/symplectic_euler.h"

#include "particles/particle_system.h"

namespace particles {

StepStats SymplecticEulerIntegrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = positionsOf(system);
  Eigen::VectorXd& v = velocitiesOf(system);
  system.acceleration(x, v, a_);
  v += dt * a_;
  x += dt * v;
  lastStep_ = dt;
  return system.takeEvaluationStats();
}

}  // namespace particles

#include "particles/integrators/midpoint.h"

#include "particles/particle_system.h"

namespace particles {

StepStats MidpointIntegrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = positionsOf(system);
  Eigen::VectorXd& v = velocitiesOf(system);
  system.acceleration(x, v, a_);
  xMid_ = x + (0.5 * dt) * v;
  vMid_ = v + (0.5 * dt) * a_;
  system.acceleration(xMid_, vMid_, a_);
  x += dt * vMid_;
  v += dt * a_;
  lastStep_ = dt;
  return system.takeEvaluationStats();
}

}  // namespace particles

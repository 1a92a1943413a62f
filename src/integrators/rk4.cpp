#include "particles/integrators/rk4.h"

#include "particles/particle_system.h"

namespace particles {

// For y = (x, v) and y' = (v, a(x, v)), the four stages are evaluated at
// y, y + (h/2) k1, y + (h/2) k2, y + h k3; dx_, dv_ accumulate the weighted sum.
StepStats Rk4Integrator::step(ParticleSystem& system, double dt) {
  Eigen::VectorXd& x = system.positions();
  Eigen::VectorXd& v = system.velocities();
  x0_ = x;
  v0_ = v;

  system.acceleration(x0_, v0_, a_);  // k1 = (v0, a)
  dx_ = v0_;
  dv_ = a_;
  xs_ = x0_ + (0.5 * dt) * v0_;
  vs_ = v0_ + (0.5 * dt) * a_;

  system.acceleration(xs_, vs_, a_);  // k2 = (vs, a)
  dx_ += 2.0 * vs_;
  dv_ += 2.0 * a_;
  xs_ = x0_ + (0.5 * dt) * vs_;
  vs_ = v0_ + (0.5 * dt) * a_;

  system.acceleration(xs_, vs_, a_);  // k3
  dx_ += 2.0 * vs_;
  dv_ += 2.0 * a_;
  xs_ = x0_ + dt * vs_;
  vs_ = v0_ + dt * a_;

  system.acceleration(xs_, vs_, a_);  // k4
  dx_ += vs_;
  dv_ += a_;

  x = x0_ + (dt / 6.0) * dx_;
  v = v0_ + (dt / 6.0) * dv_;
  lastStep_ = dt;
  return system.takeEvaluationStats();
}

}  // namespace particles

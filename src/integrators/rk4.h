#pragma once
#include <Eigen/Core>

#include "particles/integrator.h"

namespace particles {

// classic Runge–Kutta: k1..k4 at t, t + h/2, t + h/2, t + h; y ← y + h (k1 + 2k2 + 2k3 + k4)/6
class Rk4Integrator : public Integrator {
 public:
  const char* name() const override { return "rk4"; }
  StepStats step(ParticleSystem& system, double dt) override;

 private:
  Eigen::VectorXd xs_, vs_, xt_, vt_, a_, dx_, dv_;  // stage points (xs, vs), (xt, vt)
};

}  // namespace particles

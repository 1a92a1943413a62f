#pragma once
#include <Eigen/Core>

#include "particles/integrator.h"

namespace particles {

// y_mid = y + (h/2) f(y),  y ← y + h f(y_mid)
class MidpointIntegrator : public Integrator {
 public:
  const char* name() const override { return "midpoint"; }
  StepStats step(ParticleSystem& system, double dt) override;

 private:
  Eigen::VectorXd a_, xMid_, vMid_;
};

}  // namespace particles

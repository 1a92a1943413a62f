#pragma once
#include <Eigen/Core>

#include "particles/integrator.h"

namespace particles {

// x ← x + h v,  v ← v + h a(x, v)   (both from the old state)
class ExplicitEulerIntegrator : public Integrator {
 public:
  const char* name() const override { return "euler"; }
  StepStats step(ParticleSystem& system, double dt) override;

 private:
  Eigen::VectorXd a_;
};

}  // namespace particles

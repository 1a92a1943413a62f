#pragma once
#include <Eigen/Core>

#include "particles/integrator.h"

namespace particles {

// v ← v + h a(x, v),  x ← x + h v
// (position with the new velocity). This is what the seed report calls "Euler".
// It is first order but symplectic: on a conservative system its energy error
// stays bounded where explicit Euler's grows.
class SymplecticEulerIntegrator : public Integrator {
 public:
  const char* name() const override { return "symplectic-euler"; }
  StepStats step(ParticleSystem& system, double dt) override;

 private:
  Eigen::VectorXd a_;
};

}  // namespace particles

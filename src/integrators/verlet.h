#pragma once
#include <Eigen/Core>

#include "particles/integrator.h"
#include "step_continuation.h"

namespace particles {

// Velocity Verlet with a predicted velocity for velocity-dependent forces:
//   x⁺ = x + h v + (h²/2) a(x, v)
//   ṽ  = v + h a(x, v)                      (explicit Euler prediction)
//   v⁺ = v + (h/2) [a(x, v) + a(x⁺, ṽ)]
// For forces of x alone ṽ is never read and this is the symplectic,
// time-reversible velocity Verlet (order 2, bounded energy error). Plain
// velocity Verlet evaluates a(x⁺, v) with the old velocity and drops to first
// order when there is damping, drag or a constraint solve (its J̇q̇ and k_d Ċ
// terms read q̇); with the predictor the velocity update is Heun's trapezoid
// and stays second order (measured in tests/test_integrators_implicit.cpp:
// slope ≈ 2 on the damped oscillator too).
// a(x⁺, ṽ) is kept for the next step's a(x, v) when the system is untouched in
// between (no collision, drag, restore, torn spring or force that follows the
// clock; step_continuation.h): one evaluation per step. Its O(h²)
// velocity error enters v⁺ at O(h³) per step, so the order is unchanged.
class VerletIntegrator : public Integrator {
 public:
  const char* name() const override { return "verlet"; }
  StepStats step(ParticleSystem& system, double dt) override;

 private:
  Eigen::VectorXd a0_, a1_, vPredicted_;
  StepContinuation continuation_;  // the system whose acceleration a0_ holds
};

}  // namespace particles

#pragma once
#include <Eigen/Core>

#include "particles/integrator.h"
#include "particles/integrators/rk4.h"

namespace particles {

// RK4 with step doubling. From y = (x, v) one RK4 step of h gives y_big and two
// of h/2 give y_small; their difference estimates the local error of y_small,
//   e = (y_small − y_big)/15            (RK4 error ∝ h⁵, 2⁴ − 1 = 15),
// and y_small + e (Richardson extrapolation, fifth order) is kept. The step is
// accepted when  max_i |e_i| / (tol·(1 + |y_i|)) = err ≤ 1, and the next step is
//   h ← h · clamp(0.9·err^(−1/5), 0.2, 5).
// A rejected step restores the saved y and retries with the smaller h: nothing
// of it is ever applied. step(system, dt) covers dt with as many internal steps
// as needed (the last one shortened to land on dt without shrinking the
// remembered h); the internal step persists across calls. A step the
// controller would cut below IntegratorSettings::minStepFraction·dt, or more
// than maxStepsPerCall attempts in one call, ends the call early with
// StepFailure::StepBelowFloor or WorkCapReached (the state is then that of the
// last accepted internal step).
class AdaptiveRk4Integrator : public Integrator {
 public:
  const char* name() const override { return "adaptive-rk4"; }
  void configure(const IntegratorSettings& settings) override;
  StepStats step(ParticleSystem& system, double dt) override;

  double tolerance() const { return tolerance_; }
  // The step the next attempt starts from (0: start from the first dt).
  double internalStep() const { return h_; }
  void setInternalStep(double h) { h_ = h; }
  long acceptedSteps() const { return accepted_; }  // totals since construction
  long rejectedSteps() const { return rejected_; }
  // Accepted internal steps of the last step() call, in order.
  const std::vector<double>& lastAcceptedSteps() const { return history_; }

 private:
  double tolerance_ = IntegratorSettings{}.tolerance;
  double minStepFraction_ = IntegratorSettings{}.minStepFraction;
  long maxStepsPerCall_ = IntegratorSettings{}.maxStepsPerCall;
  double h_ = 0.0;
  long accepted_ = 0, rejected_ = 0;
  std::vector<double> history_;
  Rk4Integrator rk4_;
  Eigen::VectorXd x0_, v0_, xBig_, vBig_;
};

}  // namespace particles

#pragma once
#include <array>

#include <Eigen/Core>

#include "particles/integrator.h"
#include "step_continuation.h"

namespace particles {

// Dormand–Prince 5(4) (Hairer, Nørsett & Wanner, Solving ODEs I, II.4 and II.5):
// seven stages k₁…k₇ of y = (x, v), y' = (v, a(x, v)); the fifth-order
// solution y₁ = y₀ + h Σ bᵢ kᵢ is kept and the embedded fourth-order one gives
// the error estimate  e = h Σ eᵢ kᵢ  (eᵢ = bᵢ − b̂ᵢ). k₇ = f(y₁) is the next
// step's k₁ (FSAL): six evaluations per accepted step.
//
// Error norm (HNW II.4, eq. 4.11), mixed absolute and relative with one
// tolerance: err = sqrt( (1/N) Σ_i (e_i / sc_i)² ),  sc_i = tol·(1 + max(|y₀_i|, |y₁_i|)).
// A step is accepted when err ≤ 1. PI controller (HNW II.4, "Automatic step
// size control", the stabilised controller of DOPRI5 with β = 0.04):
//   h_new = h · clamp(0.9 · err^(−α) · err_prev^β, 0.2, 10),  α = 1/5 − 0.75 β,
// with err_prev the error of the last accepted step; after a rejection the
// step does not grow.
//
// step(system, dt) covers the output interval dt with as many internal steps
// as the tolerance needs; the internal step is carried from call to call and
// never cut at an output time. The internal solution runs ahead of the output
// and the state at the output time is read from its dense output (HNW II.6,
// the fourth-order continuous extension of DOPRI5), so a call whose output
// time falls inside the last accepted step takes no step and evaluates
// nothing. The internal solution carries on between calls only while the
// system holds the state the last call returned (a collision, a drag or a
// restore restarts it there, so dense output never spans such an event). A
// restart begins from the last accepted internal step capped by dt, not
// from the controller's proposal after it, which an event-free stretch can
// grow without bound. The first call picks its step with HNW's
// starting-step estimate (II.4). A step
// the controller would cut below settings.dopri5.minStepFraction·dt, or more than
// settings.dopri5.maxStepsPerCall attempts in one call, ends the call early with
// StepFailure::StepBelowFloor or WorkCapReached; the state is then that of
// the last accepted internal step.
//
// With Dopri5Settings::adaptive = false every call is one step of dt (for order tests).
class Dopri5Integrator : public Integrator {
 public:
  const char* name() const override { return "dopri5"; }
  // Takes IntegratorSettings::dopri5 (validated first).
  void configure(const IntegratorSettings& settings) override;
  const Dopri5Settings& settings() const { return settings_; }
  StepStats step(ParticleSystem& system, double dt) override;

  double internalStep() const { return h_; }  // the step the next attempt starts from (0: not chosen yet)

 private:
  // One trial step of h from (x0_, kx_[0]) with k₁ in kx_[0], kv_[0] (x's
  // derivative is the velocity, so kx_[j] is stage j's velocity); leaves y₁ in
  // (x1_, kx_[6]) and k₇ in kx_[6], kv_[6], and returns err (the norm above).
  double trial(ParticleSystem& system, double h);
  double initialStep(ParticleSystem& system, double dt);
  // The state at t₀ + θh, θ ∈ [0, 1], inside the last accepted step (from
  // its stages, still in kx_, kv_).
  void denseOutput(double theta, Eigen::VectorXd& x, Eigen::VectorXd& v) const;

  Dopri5Settings settings_;
  double h_ = 0.0, errPrevious_ = 1e-4;
  double accepted_ = 0.0;  // the last accepted internal step (0: none yet)
  std::array<Eigen::VectorXd, 7> kx_, kv_;  // stage derivatives of x (the stage velocities) and v
  // (x0_, kx_[0]): the internal solution, lead_ (s) ahead of the output state;
  // x1_ a trial's end positions, xs_ a stage's; vs_, a_ the starting step's probe.
  Eigen::VectorXd x0_, x1_, xs_, vs_, a_;
  double lead_ = 0.0;
  double denseStep_ = 0.0;  // length of the last accepted step
  // The output state last returned: the internal solution (and its k₁) is
  // continued only while the system still holds it.
  StepContinuation continuation_;
};

}  // namespace particles

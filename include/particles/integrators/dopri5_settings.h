#pragma once
// Dormand–Prince 5(4)'s settings (particles/integrators/dopri5.h), held in
// IntegratorSettings so that makeIntegrator reaches them as it reaches every
// other scheme's.
namespace particles {

struct Dopri5Settings {
  // Local error allowed per internal step, mixed absolute and relative —
  // error_i against tolerance·(1 + |y_i|) for every component of y = (x, v);
  // dopri5.h gives the norm.
  // 2e-5, the tightest value of the 1–2–5 series at which dopri5 on the
  // 80-rod chain at dt 0.01 keeps within the engine's cost target of 1.6 RK4
  // steps: 29 internal steps and 1 rejected per 30 output steps, 6.0
  // evaluations per output step against RK4's 4, 1.54 RK4 steps in
  // instructions (tests/bench/bench_step.cpp, scripts/callgrind-step.sh); it
  // ends 0.35 s 4.8× closer to a tight reference than RK4 at that dt does
  // (test Dopri5.TheDefaultToleranceBeatsRk4AtTheScenesStep prints both
  // errors). At 1e-5 it took 33 internal steps (6.6 evaluations, 1.70 RK4
  // steps) for 8.6× RK4's accuracy. The global error follows the tolerance
  // (report, §3.4 "Accuracy: work against precision").
  double tolerance = 2e-5;
  // Below this the error estimate is dominated by rounding (the stages differ
  // by a few ulps of y): a smaller tolerance is refused rather than chased.
  static constexpr double minTolerance = 1e-13;
  // Floor of the internal step, as a fraction of the interval dt of one call:
  // a step the controller would shrink below it fails the call with
  // StepFailure::StepBelowFloor instead of being accepted anyway.
  double minStepFraction = 1e-9;
  // Work cap: internal steps (accepted and rejected) one call may attempt
  // before it fails with StepFailure::WorkCapReached.
  long maxStepsPerCall = 100000;
  // false: every call is one step of dt, no error control (order tests).
  bool adaptive = true;

  void validate() const;  // throws naming the bad field
};

}  // namespace particles

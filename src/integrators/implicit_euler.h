#pragma once
#include <memory>

#include "particles/integrator.h"

namespace particles {

// Backward Euler with the constraints inside the solve (after Baraff & Witkin,
// "Large Steps in Cloth Simulation", with Newton on the constraints). One step
// of h from (x₀, v₀) finds v⁺ and the constraint impulses ν with x⁺ = x₀ + h v⁺,
//   M (v⁺ − v₀) − h f(x⁺, v⁺) + Ḡᵀ ν = 0,   C(x⁺) = (1 − β) C(x₀),
// Ḡ the discrete gradient of C between x₀ and x⁺, by Newton passes on a
// symmetric quasi-definite system (LDLᵀ), or Jacobi-preconditioned CG on the
// momentum block alone without constraints. Its energy cannot rise: drag,
// gravity and springs lose at least ½|v⁺ − v₀|²_M a step, at any h, and the
// constraint impulses do no work on a step that keeps C fixed. The derivation,
// the stopping test and the choice of Jacobians and solver are written above
// the step's phases in src/integrators/implicit_euler.cpp.
// A force without Jacobians is refused with an exception naming it.
class ImplicitEulerIntegrator : public Integrator {
 public:
  // Every force enters through its Jacobians: the mouse joint may be as stiff as it likes.
  // Takes IntegratorSettings::implicitEuler (validated first).
  void configure(const IntegratorSettings& settings) override;
  const ImplicitEulerSettings& settings() const { return settings_; }

  ImplicitEulerIntegrator();
  ~ImplicitEulerIntegrator() override;

  const char* name() const override { return "implicit-euler"; }
  StepStats step(ParticleSystem& system, double dt) override;

  // Throws std::invalid_argument naming the first force without Jacobians.
  static void requireJacobians(const ParticleSystem& system);

  int lastPasses() const;  // Newton solves in the last step
  // Of the committed step: max |C − (1 − β) C(x₀)| / (|J| r) over constraints
  // with a free particle, and max |W R₁| over its velocity scale (the stopping test);
  // both ≤ constraintTolerance unless the passes ran out. 0 without constraints.
  double lastConstraintResidual() const;
  double lastMomentumResidual() const;

 private:
  ImplicitEulerSettings settings_;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace particles

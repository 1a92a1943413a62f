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
enum class ImplicitLinearSolver {
  Direct,             // LDLᵀ of the Newton passes' KKT matrix
  ConjugateGradient,  // Jacobi-preconditioned CG on A; constrained systems use Direct
};

struct ImplicitEulerSettings {
  // true: constraints inside the solve (as above). false: the constraint forces of
  // the explicit solve (ConstraintSolver, k_s/k_d feedback) at the start state,
  // held fixed through the step — the lagged scheme, kept for comparison.
  bool coupledConstraints = true;
  double stabilization = 1.0;          // β ∈ [0, 1]: fraction of C(x₀) removed in one step
  int constraintPasses = 20;           // most Newton solves per step (≥ 1)
  double constraintTolerance = 1e-10;  // relative residuals that end the passes (the stopping test)
  // Add G, the constraints' geometric stiffness (Tournier et al.
  // 2015). Without it the passes are Gauss–Newton and stall or diverge on a
  // long chain, whose tension h²|λ| ∇²C outweighs M.
  bool geometricStiffness = true;
  double compliance = 1e-10;           // ε, relative to diag(J W Jᵀ)
  ImplicitLinearSolver solver = ImplicitLinearSolver::ConjugateGradient;  // measured: tests/bench/bench_solvers.cpp
  double cgTolerance = 1e-6;           // relative residual of the CG solves
  int cgMaxIterations = 1000;

  void validate() const;  // throws naming the bad field
};

class ImplicitEulerIntegrator : public Integrator {
 public:
  ImplicitEulerSettings settings;

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
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace particles

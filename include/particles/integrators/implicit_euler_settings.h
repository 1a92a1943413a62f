#pragma once
// Implicit Euler's settings (particles/integrators/implicit_euler.h), held in
// IntegratorSettings so that makeIntegrator reaches them as it reaches every
// other scheme's.
namespace particles {

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

}  // namespace particles

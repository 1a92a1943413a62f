#pragma once
#include <memory>

#include "particles/integrator.h"

namespace particles {

// Backward Euler with the constraints inside the solve (after Baraff & Witkin,
// "Large Steps in Cloth Simulation", with Newton on the constraints).
//
// The scheme. One step of h from (x₀, v₀) finds v⁺ and the constraint
// impulses ν (ν = −h λ, one per constraint) with x⁺ = x₀ + h v⁺ and
//   R₁ = M (v⁺ − v₀) − h f(x⁺, v⁺) + Ḡᵀ ν = 0          (momentum)
//   R₂ = C(x⁺) − (1 − β) C(x₀)           = 0          (positions; β = 1: C(x⁺) = 0)
// where Ḡ is the discrete gradient of C between x₀ and x⁺ (Gonzalez 1996):
//   Ḡ = J(x_m) + [C(x⁺) − C(x₀) − J(x_m) Δx] Δxᵀ/|Δx|²,  x_m = (x₀ + x⁺)/2,  Δx = x⁺ − x₀,
// so that Ḡ Δx = C(x⁺) − C(x₀) exactly (for the quadratic rods and wires the
// bracket vanishes and Ḡ = J(x_m)).
//
// Why it cannot gain energy. With E = ½ vᵀM v + V(x) and f = −∇V + f_d,
// R₁ = 0 and R₂ = 0 give, exactly,
//   E⁺ − E₀ = −½ |v⁺ − v₀|²_M                        (backward Euler's numerical dissipation)
//             − [∇V(x⁺)·Δx − (V(x⁺) − V(x₀))]          (≥ 0 when V is convex along the step)
//             + h v⁺·f_d(x⁺, v⁺)                       (≤ 0 for drag and spring damping)
//             + β Σ_k ν_k C_k(x₀)/h                     (the constraint impulses' work),
// because v⁺·Ḡᵀν = Σ ν_k (C_k(x⁺) − C_k(x₀))/h. The last term is the only one
// that can be positive, and it is bounded by the violation C(x₀) the previous
// step left, which the Newton passes hold below `constraintTolerance`: the
// impulses do no work on a step that keeps C fixed. (Along J(x⁺), the plain
// backward-Euler direction, they would do (ν/2h) Δxᵀ∇²C Δx of work, which is
// positive for a rod in compression; a Baumgarte feedback k_s C + k_d Ċ or a
// projection after the step adds energy the same way; hence neither is used.)
// Gravity, zero-length springs and drag therefore lose energy on every step,
// at any h, by at least ½|Δv|²_M; a spring under compression has a concave
// transverse potential, whose bracket is then bounded by ½ h² Δv-sized terms
// but not signed.
//
// The step as phases (ImplicitEulerIntegrator::step):
//   linearise forces → gather constraint rows → assemble → Newton passes → commit.
// Each Newton pass is linearised at the current iterate (x̃ = x₀ + h v̄, v̄, ν̄):
//   [A + G   J̃ᵀ] [δv]   [−R₁]     A = M − h D − h² K (D = ∂f/∂v, K = ∂f/∂x at the iterate),
//   [J̃      −E ] [δν] = [−R₂/h],  J̃ = J(x̃),  G = (h/2) Σ max(ν̄_k, 0) ∇²C_k(x_m),
// with E = ε·diag(J̃ W J̃ᵀ) a tiny compliance on the increments (it regularises
// the solve without moving its solution). The first iterate is v̄ = v₀ with
// the last step's impulses; its force and Jacobians are Baraff & Witkin's, taken
// at the start state (f(x₀ + h v₀) ≈ f₀ + h K v₀). Later passes evaluate the
// forces, K, D, C and J at the iterate. The passes stop when, over every
// constraint with a free particle,
//   max |C(x̃) − (1 − β) C(x₀)| / (|J̃| r) ≤ constraintTolerance   and
//   max |W R₁| ≤ constraintTolerance · max(|v̄| + h|W|(|f| + Σ_c|K_dc||Δx_dc|) + |W Ḡᵀν̄|)
// over the free DOFs; Σ_c|K_dc||Δx_dc| (a spring's k times its length) is the
// size of the force terms that cancel in f near equilibrium, which sets the
// round-off floor of R₁ (without it a stiff cloth hanging still could not get
// below ~1e-9 and ran every pass),
// or after constraintPasses solves (the step is then committed as it stands
// and lastConstraintResidual() says how far it got). A constraint whose
// particles are all pinned (or whose J vanishes) is left out: its impulse is 0,
// it does not count in the stopping test, and it moves nothing — even when it
// cannot be satisfied (a rod between two pins at the wrong length).
// Without constraints there is one pass: Baraff & Witkin's linearly implicit
// step, exact backward Euler for linear forces.
//
// Which Jacobians and which solver:
// - K and D come from Force::addDefiniteJacobians: symmetric negative
//   semi-definite, so A + G is symmetric positive definite on the free degrees
//   of freedom and the matrix above is symmetric quasi-definite for ε > 0:
//   every symmetric permutation has an LDLᵀ factorisation without pivoting
//   (Vanderbei 1995). ε also keeps redundant constraints solvable. The matrix
//   uses J̃ in both off-diagonal blocks (R₁'s exact derivative has Ḡᵀ): the
//   passes then converge to the step above with the ν error contracting by
//   about (h|u|/2r)² per pass, u a rod's relative velocity.
// - Pinned particles (inverse mass 0) are filtered: their rows and columns of A
//   are the identity with a zero right-hand side, so δv = 0 there.
// - The sparsity pattern is analysed once and reused while the forces,
//   constraints and pins keep the same structure.
// - Without constraints, Jacobi-preconditioned conjugate gradient on A alone,
//   warm-started from the last Δv, is the default: measured on 8-way cloth
//   (tests/bench/bench_solvers.cpp) it needs ~5 iterations on ordinary cloth
//   and beats the direct solve (O(n^1.5) fill) by 4-10×; on stiff cloth
//   (k_s h²/m ≫ 1) it needs a few hundred and the two are about even.
// A force without Jacobians is refused with an exception naming it.
enum class ImplicitLinearSolver {
  Direct,             // LDLᵀ of the KKT matrix above
  ConjugateGradient,  // Jacobi-preconditioned CG on A; constrained systems use Direct
};

struct ImplicitEulerSettings {
  // true: constraints inside the solve (above). false: the constraint forces of
  // the explicit solve (ConstraintSolver, k_s/k_d feedback) at the start state,
  // held fixed through the step — the lagged scheme, kept for comparison.
  bool coupledConstraints = true;
  double stabilization = 1.0;          // β ∈ [0, 1]: fraction of C(x₀) removed in one step
  int constraintPasses = 20;           // most Newton solves per step (≥ 1)
  double constraintTolerance = 1e-10;  // relative residuals that end the passes (see above)
  // Add G (above), the constraints' geometric stiffness (Tournier et al.
  // 2015). Without it the passes are Gauss–Newton and stall or diverge on a
  // long chain, whose tension h²|λ| ∇²C outweighs M.
  bool geometricStiffness = true;
  double compliance = 1e-10;           // ε, relative to diag(J W Jᵀ)
  ImplicitLinearSolver solver = ImplicitLinearSolver::ConjugateGradient;  // measured: see above
  double cgTolerance = 1e-6;           // relative residual of the CG solves
  int cgMaxIterations = 1000;

  void validate() const;  // throws naming the bad field
};

class ImplicitEulerIntegrator : public Integrator {
 public:
  bool couplesContactsWithConstraints() const override { return false; }
  // Every force enters through its Jacobians: the mouse joint may be as stiff as it likes.
  double explicitForceStep(double) const override { return 0.0; }
  ImplicitEulerSettings settings;

  ImplicitEulerIntegrator();
  ~ImplicitEulerIntegrator() override;

  const char* name() const override { return "implicit-euler"; }
  StepStats step(ParticleSystem& system, double dt) override;

  // Throws std::invalid_argument naming the first force without Jacobians.
  static void requireJacobians(const ParticleSystem& system);

  int lastPasses() const;  // Newton solves in the last step
  // Of the committed step: max |C − (1 − β) C(x₀)| / (|J| r) over constraints
  // with a free particle, and max |W R₁| over its velocity scale (see above);
  // both ≤ constraintTolerance unless the passes ran out. 0 without constraints.
  double lastConstraintResidual() const;
  double lastMomentumResidual() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace particles

#pragma once
#include <vector>

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "particles/force.h"
#include "particles/integrator.h"

namespace particles {

// Backward Euler after Baraff & Witkin, "Large Steps in Cloth Simulation":
// one linearised Newton step per time step with the constraints inside it.
// With A = M − h D − h² K (D = ∂f/∂v, K = ∂f/∂x at the start of the step) the
// velocity change Δv and the constraint impulses ν (= −h λ) solve
//   [ A  Jᵀ ] [Δv]   [ h (f₀ + h K v₀) ]
//   [ J  −E ] [ν ] = [ c − J v₀        ],    v⁺ = v₀ + Δv,  x⁺ = x₀ + h v⁺,
// where c is the velocity the constraints must have for C(x⁺) = 0. On the
// first pass, from the second-order Taylor expansion at x₀,
//   C(x₀ + h v⁺) = C + h J v⁺ + (h²/2) v⁺ᵀ (∂²C/∂q²) v⁺,  with J̇(v) v = vᵀ(∂²C/∂q²)v,
// c = −β C/h − (h/2) J̇(v₀) v₀: the curvature term keeps a bead on a circular
// wire, which the chord h v⁺ would otherwise leave by (h|v|)²/2r every step.
// When a step moves particles by a good part of a rod length (a chain at
// dt = 0.2) the linearisation at x₀ is not enough, so further passes do Newton
// on the constraints alone: with x̃ = x₀ + h v̄ from the last pass, J̃ = J(x̃),
// C̃ = C(x̃), solve the same system with J̃ and  J̃ v⁺ = J̃ v̄ − β C̃/h, until
// max |C̃|/r ≤ constraintTolerance or constraintPasses solves; the maximum
// skips constraints whose particles are all pinned (no pass can move them). The force part
// (A, f₀, K) stays linearised at the start of the step, as in Baraff & Witkin;
// the constraint force acts along J̃ᵀ, its direction at the end of the step.
//
// Which Jacobians and which solver:
// - K and D come from Force::addDefiniteJacobians: symmetric negative
//   semi-definite (springs under compression lose their transverse term, the
//   non-symmetric damping part of ∂f/∂x is dropped). A is then symmetric
//   positive definite on the free degrees of freedom, and the matrix above is
//   symmetric quasi-definite once E = ε·diag(J W Jᵀ) > 0 is a tiny compliance
//   (ε = 1e-10): every symmetric permutation of it has an LDLᵀ factorisation
//   without pivoting (Vanderbei 1995), so Eigen's SimplicialLDLT with its AMD
//   ordering solves it directly. ε also keeps redundant constraints (a taut
//   chain between two wires) solvable. SparseLU or BiCGSTAB on the exact,
//   non-symmetric Jacobians would be the alternative at several times the cost.
// - Pinned particles (inverse mass 0) are filtered: their rows and columns of A
//   become the identity with a zero right-hand side, so Δv = 0 there, and their
//   blocks of J are left out. A constraint on pinned particles only is the
//   row −ν = 0.
// - The sparsity pattern is analysed once and reused while the forces,
//   constraints and pins keep the same structure; each step only refills the
//   values and refactorises numerically.
// - Without constraints, Jacobi-preconditioned conjugate gradient on A alone,
//   warm-started from the last Δv, is the default: measured on 8-way cloth
//   (tests/bench/bench_solvers.cpp) it needs ~5 iterations on ordinary cloth
//   and beats the direct solve (O(n^1.5) fill) by 4-10×; on stiff cloth
//   (k_s h²/m ≫ 1) it needs a few hundred and the two are about even. Eigen's
//   IncompleteCholesky as preconditioner halved the iterations on stiff cloth
//   but cost more than it saved (its factorisation is list-based) and was dropped.
// A force without Jacobians is refused with an exception naming it.
enum class ImplicitLinearSolver {
  Direct,             // SimplicialLDLT of the KKT matrix above
  ConjugateGradient,  // Jacobi-preconditioned CG on A; constrained systems use Direct
};

struct ImplicitEulerSettings {
  // true: constraints inside the solve (above). false: the constraint forces of
  // the explicit solve (ConstraintSolver, k_s/k_d feedback) at the start state,
  // held fixed through the step — the lagged scheme, kept for comparison.
  bool coupledConstraints = true;
  double stabilization = 1.0;   // β: fraction of C removed in one step
  int constraintPasses = 6;     // most solves per step (≥ 1)
  double constraintTolerance = 1e-4;  // max |C(x⁺)|/r that ends the passes early
  // Add G = h Σ max(ν_k, 0) ∂²C_k/∂q² to A (the constraints' geometric
  // stiffness, Tournier et al. 2015). Without it the passes are Gauss–Newton and
  // stall or diverge on a long chain, whose tension h²|λ| ∂²C outweighs M.
  bool geometricStiffness = true;
  double compliance = 1e-10;    // ε, relative to diag(J W Jᵀ)
  ImplicitLinearSolver solver = ImplicitLinearSolver::ConjugateGradient;  // measured: see above
  double cgTolerance = 1e-6;    // relative residual of the CG solvers
  int cgMaxIterations = 1000;

  void validate() const;  // throws naming the bad field
};

class ImplicitEulerIntegrator : public Integrator {
 public:
  ImplicitEulerSettings settings;

  const char* name() const override { return "implicit-euler"; }
  StepStats step(ParticleSystem& system, double dt) override;

  // Throws std::invalid_argument naming the first force without Jacobians.
  static void requireJacobians(const ParticleSystem& system);

  int lastPasses() const { return passes_; }           // solves in the last step
  bool lastUsedDirect() const { return usedDirect_; }
  const Eigen::VectorXd& lastImpulses() const { return nuOld_; }  // ν = −h λ per constraint

 private:
  using SparseMatrix = Eigen::SparseMatrix<double>;
  void gatherConstraints(ParticleSystem& system, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  double worstRelativeViolation(ParticleSystem& system, const Eigen::VectorXd& x,
                                const Eigen::VectorXd& v) const;
  bool patternMatches(int n, const Eigen::VectorXd& inverseMass, bool withConstraints,
                      bool direct) const;
  void buildPattern(ParticleSystem& system, bool withConstraints, bool direct);
  void jacobiConjugateGradient(const Eigen::VectorXd& b);
  void addGeometricStiffness(ParticleSystem& system, const Eigen::VectorXd& x, double h);
  void addGeometricStiffnessTimes(ParticleSystem& system, const Eigen::VectorXd& x,
                                  const Eigen::VectorXd& dv, double h, Eigen::VectorXd& out);
  bool fillValues(int n, double h, const Eigen::VectorXd& mass, const Eigen::VectorXd& inverseMass,
                  bool withConstraints, Eigen::VectorXd* Kv);

  // Force and constraint data of the current step.
  Triplets dfdx_, dfdv_;
  std::vector<int> rowStart_, entryParticle_;
  std::vector<Eigen::Vector2d> J_, Jdot_;
  Eigen::VectorXd C_;

  // Pattern cache: the triplet positions and constraint structure it was built
  // for, and where each value lands in matrix_.valuePtr() (−1: dropped).
  std::vector<int> xRow_, xCol_, vRow_, vCol_, xSlot_, vSlot_;
  std::vector<int> diagonalSlot_, jSlot_, complianceSlot_, gSlot_;
  std::vector<int> cachedRowStart_, cachedEntryParticle_;
  std::vector<char> cachedPinned_;
  bool cachedWithConstraints_ = false;
  bool analysed_ = false;
  SparseMatrix matrix_;     // upper triangle of the KKT matrix (or of A), permuted
  Eigen::VectorXi order_;   // unknown i is row order_[i] of matrix_
  bool cachedDirect_ = false;
  // SimplicialLDLT that factorises the stored, already permuted matrix in
  // place (Eigen's factorize() makes a temporary copy, allocating each step).
  struct InPlaceLdlt : Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>> {
    void factorizeInPlace(const SparseMatrix& upper) { this->template factorize_preordered<true>(upper); }
  };
  InPlaceLdlt ldlt_;
  bool ldltAnalysed_ = false;
  Eigen::VectorXd permutedRhs_, inverseDiagonal_, cgR_, cgZ_, cgP_, cgAp_;

  Eigen::VectorXd f0_, Kv_, rhs_, z_, x0_, v0_, vBar_, a_;
  // solution_: (Δv, ν) of the last solve in the stored numbering (CG's warm start).
  Eigen::VectorXd solution_, xTrial_, rhsForces_, dvOld_, nuOld_, probe_;
  std::vector<Eigen::Vector2d> probeJ_, probeJdot_;
  int iterations_ = 0, passes_ = 0;
  double cgResidual_ = 0.0;
  bool usedDirect_ = true;
};

}  // namespace particles

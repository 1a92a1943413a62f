#pragma once
// The constraint solve: with forces Q accumulated, find λ from
//   (J W Jᵀ) λ = −J̇ q̇ − J W Q − k_s C − k_d Ċ
// and add the constraint force Q̂ = Jᵀ λ. Three ways to solve it (settings):
// - matrix-free conjugate gradient: J W Jᵀ is applied as an operator from the
//   per-constraint blocks, never formed (plain or Jacobi-preconditioned);
// - conjugate gradient preconditioned by an incomplete Cholesky factor of the
//   assembled J W Jᵀ (exact for a chain, whose J W Jᵀ is tridiagonal);
// - a sparse direct solve: SimplicialLDLT of the assembled J W Jᵀ, its
//   sparsity pattern analysed once per constraint structure and only
//   refactorised numerically each solve.
// Rows whose diagonal is zero (every particle in them pinned) get λ = 0 in all three.
// When J W Jᵀ loses rank the direct solve is damped, (J W Jᵀ + μ I) λ = b with
// μ = 1e-6·max diag, a bounded approximation of the least-squares λ (see
// ConstraintSolver::directSolve in the source for its effect on accuracy).
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "particles/constraint.h"

namespace particles {

enum class SolveMethod {
  ConjugateGradient,  // iterative, with the preconditioner below
  Direct,             // SimplicialLDLT of the assembled J W Jᵀ
};

enum class Preconditioner {
  None,                // plain CG
  Jacobi,              // diagonal of J W Jᵀ, which the blocks give at no extra cost
  IncompleteCholesky,  // Eigen::IncompleteCholesky of the assembled J W Jᵀ
};

struct SolverSettings {
  double tolerance = 1e-8;       // stop when |r| ≤ tolerance·|b| (relative residual)
  int maxIterations = 0;         // CG iteration cap; 0 means 4m + 100 for m constraints
  double stiffness = 60.0;       // k_s of the feedback term, 1/s² (squared-rod units aside)
  double damping = 10.0;         // k_d of the feedback term, 1/s
  bool warmStart = true;         // start CG from the previous λ
  // Default measured in tests/bench/bench_solvers.cpp (see the comment there).
  SolveMethod method = SolveMethod::Direct;
  Preconditioner preconditioner = Preconditioner::Jacobi;  // for ConjugateGradient

  void validate() const;  // throws naming the bad field
};

struct SolveStats {
  int constraints = 0;     // m
  int iterations = 0;      // CG iterations of the last solve (0 for a direct solve)
  double residual = 0.0;   // relative residual |r|/|b| at exit (0 when b = 0)
  int factorizations = 0;  // numeric factorisations made (LDLᵀ, incomplete Cholesky)
  // λ or the residual came out non-finite (a blown-up state, or b overflowing):
  // λ is set to 0 so that no NaN reaches the state, and the step reports
  // StepFailure::SolveFailed, which the tools treat as a divergence.
  bool failed = false;
  // J W Jᵀ had lost rank and the direct solve was damped (see directSolve).
  bool regularized = false;
};

using ConstraintList = std::vector<std::unique_ptr<Constraint>>;

class ConstraintSolver {
 public:
  SolverSettings settings;

  // Adds Jᵀλ to f, where f holds the accumulated forces Q on entry.
  void addConstraintForces(const Phase& s, const ConstraintList& constraints, Eigen::VectorXd& f);

  const SolveStats& stats() const { return stats_; }
  const Eigen::VectorXd& lambda() const { return lambda_; }
  void resetWarmStart() { lambda_.resize(0); }

  // The pieces of the last solve, for tests: the gathered rows as dense J and
  // J̇ (m × 2n), the right-hand side b, and A·y = J W Jᵀ y applied matrix-free.
  Eigen::MatrixXd denseJ(int particleCount) const;
  Eigen::MatrixXd denseJdot(int particleCount) const;
  const Eigen::VectorXd& rhs() const { return b_; }
  void applyOperator(const Eigen::VectorXd& y, Eigen::VectorXd& out) const;

 private:
  using SparseMatrix = Eigen::SparseMatrix<double>;
  void gather(const Phase& s, const ConstraintList& constraints);
  // Rows whose diagonal is at most `dead` are removed with λ = 0.
  int conjugateGradient(double dead, double& relativeResidual);
  // Upper triangle of P (J W Jᵀ) Pᵀ into assembled_ (P an AMD ordering), re-analysing the pattern only
  // when the constraint structure changed; dead rows get a unit diagonal.
  void assemble(double dead);
  bool directSolve(double dead, double& relativeResidual);  // false: fall back to CG

  // Rows in compressed form: entries rowStart_[k] .. rowStart_[k+1]−1 belong
  // to constraint k; each entry is one particle with its J and J̇ blocks.
  std::vector<int> rowStart_;
  std::vector<int> entryParticle_;
  std::vector<Eigen::Vector2d> J_, Jdot_;
  Eigen::VectorXd C_, Cdot_, b_, lambda_, diagonal_;
  const Eigen::VectorXd* inverseMass_ = nullptr;
  // CG scratch, kept to avoid allocation in the step loop.
  Eigen::VectorXd r_, z_, p_, Ap_;
  mutable Eigen::VectorXd scatter_;  // W Jᵀ y inside applyOperator
  SolveStats stats_;

  // Assembled P (J W Jᵀ) Pᵀ (upper triangle; constraint k at row order_[k])
  // and its factorisations. Value s of the matrix is Σ w_p J_e1·J_e2 over the
  // pairs pairStart_[s] .. pairStart_[s+1]−1.
  SparseMatrix assembled_;
  Eigen::VectorXi order_;
  Eigen::VectorXd permuted_, permutedSolution_;
  std::vector<int> pairStart_, pairFirst_, pairSecond_, diagonalSlot_;
  bool patternValid_ = false, ldltAnalysed_ = false, incompleteCholeskyUsable_ = false;
  // SimplicialLDLT whose numeric factorisation reads the (already permuted,
  // upper-triangular) matrix directly: Eigen's factorize() builds an empty
  // temporary matrix first, one heap allocation per solve.
  struct InPlaceLdlt : Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>> {
    void factorizeInPlace(const SparseMatrix& upper) { this->template factorize_preordered<true>(upper); }
    const Eigen::VectorXd& pivots() const { return this->m_diag; }  // D; vectorD() copies
  };
  using IncompleteCholesky = Eigen::IncompleteCholesky<double, Eigen::Upper, Eigen::NaturalOrdering<int>>;
  // Eigen's solvers cannot be moved; held by pointer (made on first use) so
  // that ConstraintSolver, and with it ParticleSystem, stays movable.
  std::unique_ptr<InPlaceLdlt> ldlt_;
  std::unique_ptr<IncompleteCholesky> incompleteCholesky_;
};

}  // namespace particles

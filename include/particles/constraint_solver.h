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
//   refactorised numerically each solve; for a chain (each constraint sharing
//   particles only with the ones before and after it in the list, as a rod
//   chain's rods), whose J W Jᵀ is tridiagonal, the O(m) tridiagonal LDLᵀ.
// Rows whose diagonal is zero (every particle in them pinned) get λ = 0 in all three.
// When J W Jᵀ loses rank the direct solve is damped, (J W Jᵀ + μ I) λ = b with
// μ = 1e-6·max diag, a bounded approximation of the least-squares λ (see
// ConstraintSolver::directSolve in the source for its effect on accuracy).
#include <memory>
#include <string>

#include <Eigen/Core>

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
  // CG's work bound for one solve, in products of J's entries (an iteration
  // costs about 2 × J's nonzeros): CG that reaches it unconverged falls back
  // to the direct solve, for this solve and the later ones of the same
  // constraint structure (SolveStats::directFallback). CG on a chain takes
  // about m iterations, 4m² products: at 2e7 a 2,000-rod chain keeps CG
  // (1.6e7), 3,000 rods and more fall back. 0: no bound.
  double maxCgWork = 2e7;
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
  // CG was asked for but solved directly: its work passed maxCgWork.
  bool directFallback = false;
  // The rows came from a chain of rods' own pass (src/constraints/rod_chain.h),
  // not from the generic gather.
  bool chainPass = false;
};

// What the tools say when CG falls back to the direct solve: "CG on 8000
// constraints passed its work bound (2e+07 products of J's entries in one
// solve): solved directly (LDLT) instead".
std::string directFallbackMessage(int constraints, const SolverSettings& settings);

class ConstraintSolver {
 public:
  ConstraintSolver();
  ~ConstraintSolver();
  ConstraintSolver(ConstraintSolver&&) noexcept;
  ConstraintSolver& operator=(ConstraintSolver&&) noexcept;

  SolverSettings settings;

  // Adds Jᵀλ to f, where f holds the accumulated forces Q on entry.
  void addConstraintForces(const Phase& s, const ConstraintList& constraints, Eigen::VectorXd& f);

  const SolveStats& stats() const { return stats_; }
  const Eigen::VectorXd& lambda() const { return lambda_; }
  void resetWarmStart() { lambda_.resize(0); }

  // The right-hand side b of the last solve (m).
  const Eigen::VectorXd& rhs() const { return b_; }
  // J and J̇ of the last solve as dense m × 2n matrices for n particles: for
  // checks on small systems (against finite differences, a dense solve).
  Eigen::MatrixXd denseJ(int particleCount) const;
  Eigen::MatrixXd denseJdot(int particleCount) const;

 private:
  // A·y = J W Jᵀ y applied matrix-free, from the gathered rows.
  void applyOperator(const Eigen::VectorXd& y, Eigen::VectorXd& out) const;
  // The rows, the assembled J W Jᵀ, its factorisations and the CG scratch
  // (src/linear; defined in src/constraint_solver.cpp).
  struct Workspace;
  std::unique_ptr<Workspace> work_;
  Eigen::VectorXd b_, lambda_;
  SolveStats stats_;

  // Rows whose diagonal is at most `dead` are removed with λ = 0.
  // pastWorkBound: it stopped unconverged at SolverSettings::maxCgWork.
  int conjugateGradient(double dead, double& relativeResidual, bool& pastWorkBound);
  // Fills the assembled P (J W Jᵀ) Pᵀ, rebuilding its pattern when the rows
  // changed structure; dead rows get a unit diagonal.
  void assemble(double dead);
  bool directSolve(double dead, double& relativeResidual);  // false: fall back to CG
  // Fills the rows, b and diag(J W Jᵀ); true when a chain of rods' own pass did.
  bool formSystem(const Phase& s, const ConstraintList& constraints, const Eigen::VectorXd& f);
  // A chain of constraints (each sharing particles only with its neighbours
  // in the list): J W Jᵀ is tridiagonal and solved in O(m).
  void findChain();
  void assembleChain(double dead);
};

}  // namespace particles

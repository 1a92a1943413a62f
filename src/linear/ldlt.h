#pragma once
// Sparse LDLᵀ of a symmetric matrix stored by SymmetricPattern (upper
// triangle, already permuted): Eigen's SimplicialLDLT through its public API
// with NaturalOrdering, so factorize() reads the stored matrix in place. The
// symbolic analysis (elimination tree, column counts) is done once per
// pattern; each step only factorises numerically. A shift μ factorises
// S + μ I instead (damped least squares when S has lost rank).
// With NaturalOrdering and an upper, compressed column-major matrix, Eigen's
// public factorize() uses the matrix without a copy (it only sizes an empty
// temporary), so no in-place variant reaching into its protected members is
// kept: tests/bench/bench_linear.cpp measures it saving ~0.1 µs a factorisation.
#include <memory>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>

#include "linear/symmetric_pattern.h"

namespace particles::linear {

class Ldlt {
 public:
  Ldlt();
  ~Ldlt();
  Ldlt(Ldlt&&) noexcept;
  Ldlt& operator=(Ldlt&&) noexcept;

  // Symbolic analysis of the pattern of `upper`; needed again after the pattern changes.
  void analyze(const SparseMatrix& upper);
  bool analysed() const { return analysed_; }
  void forgetAnalysis() { analysed_ = false; }
  // Numeric LDLᵀ of upper + shift·I (analysing first if needed). False when
  // a pivot is zero or the values are not finite; smallestPivot() is then meaningless.
  bool factorize(const SparseMatrix& upper, double shift = 0.0);
  // min_i D_ii of the last factorisation.
  double smallestPivot() const;
  // x = (L D Lᵀ)⁻¹ b, in the stored numbering.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

 private:
  // Eigen's SimplicialLDLT, whose public vectorD() returns D by value (a heap
  // copy each call); D is read in place here instead.
  struct Solver : Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>> {
    const Eigen::VectorXd& diagonal() const { return m_diag; }
  };
  std::unique_ptr<Solver> solver_;  // Eigen's solvers cannot be moved
  bool analysed_ = false;
};

}  // namespace particles::linear

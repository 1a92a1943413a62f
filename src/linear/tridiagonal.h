#pragma once
// LDLᵀ of a symmetric tridiagonal matrix T (T_kk = diagonal[k],
// T_{k,k+1} = T_{k+1,k} = upper[k]) plus a shift μ I, in O(m):
//   d_0 = T_00 + μ,   l_k = T_{k,k+1} / d_k,   d_{k+1} = T_{k+1,k+1} + μ − l_k T_{k,k+1};
// then T x = b by  y_k = b_k − l_{k−1} y_{k−1},  x_{m−1} = y_{m−1} / d_{m−1},
// x_k = y_k / d_k − l_k x_{k+1}. The factorisation keeps 1/d_k (one
// division a row, which the pivot recursion waits for anyway), so the back
// substitution, a recursion too, waits for a multiplication only. The constraint solve of a chain of
// constraints uses it in place of the sparse LDLᵀ (ldlt.h), with which it
// shares the interface: a failed factorisation (a zero or non-finite pivot)
// and the smallest pivot, which tells when T has lost rank. (xpbd's hanging
// lines solve their own lane-interleaved systems: xpbd/hanging_lines.h.)
#include <vector>

#include <Eigen/Core>

namespace particles::linear {

class Tridiagonal {
 public:
  // Factorises T + shift·I; false when a pivot is zero or not finite.
  bool factorize(const std::vector<double>& diagonal, const std::vector<double>& upper, double shift = 0.0);
  // min_k d_k of the last factorisation.
  double smallestPivot() const;
  // x = (L D Lᵀ)⁻¹ b (x may be b).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;
  // |T x − b| / |b| (0 when b = 0), T without the shift: one pass, no T x kept.
  static double relativeResidual(const std::vector<double>& diagonal, const std::vector<double>& upper,
                                 const Eigen::VectorXd& x, const Eigen::VectorXd& b);

 private:
  std::vector<double> inversePivot_, lower_;  // 1/d_k, l_k
  double smallestPivot_ = 0.0;
};

}  // namespace particles::linear

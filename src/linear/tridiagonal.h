#pragma once
// LDLᵀ of a symmetric tridiagonal matrix T (T_kk = diagonal[k],
// T_{k,k+1} = T_{k+1,k} = upper[k]) plus a shift μ I, in O(m):
//   d_0 = T_00 + μ,   l_k = T_{k,k+1} / d_k,   d_{k+1} = T_{k+1,k+1} + μ − l_k T_{k,k+1};
// then T x = b by  y_k = b_k − l_{k−1} y_{k−1},  x_{m−1} = y_{m−1} / d_{m−1},
// x_k = y_k / d_k − l_k x_{k+1}. The factorisation keeps 1/d_k (one division
// a row, beside the one the pivot recursion waits for), so the back
// substitution, a recursion too, waits for a multiplication only. The
// constraint solve of a chain of constraints uses it in place of the sparse
// LDLᵀ (ldlt.h), with which it shares the interface: a failed factorisation
// (a zero or non-finite pivot) and the smallest pivot, which tells when T has
// lost rank. (xpbd's hanging lines solve their own lane-interleaved systems:
// xpbd/hanging_lines.h.)
#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Core>

namespace particles::linear {

class Tridiagonal {
 public:
  // Factorises T + shift·I; false when a pivot is zero or not finite.
  bool factorize(const std::vector<double>& diagonal, const std::vector<double>& upper, double shift = 0.0);
  // The same factorisation row by row, for a caller that forms T and b in
  // order (a chain of rods' pass, whose work then hides the recursions'
  // latency): start(m, shift), row(k, T_kk, T_{k−1,k}, b_k) for k = 0 … m − 1
  // (T_{k−1,k} unused for k = 0), then usable() is what factorize() returns,
  // and backSubstitute(x) is solve(b, x) for that b: row() also does the
  // forward substitution y_k = b_k − l_{k−1} y_{k−1}.
  void start(std::size_t m, double shift = 0.0);
  void row(std::size_t k, double diagonal, double upperBefore, double rhs) {
    double d = diagonal + shift_;
    if (k > 0) {
      const double l = upperBefore / pivot_;  // l_{k−1} = T_{k−1,k} / d_{k−1}
      lower_[k - 1] = l;
      d -= l * upperBefore;
      rhs -= l * forward_;
    }
    usable_ = usable_ && d != 0.0 && std::isfinite(d);
    smallestPivot_ = std::min(smallestPivot_, d);
    pivot_ = d;
    forward_ = y_[k] = rhs;
    inversePivot_[k] = 1.0 / d;  // off the recursion's path
  }
  bool usable() const { return usable_; }
  // min_k d_k of the last factorisation.
  double smallestPivot() const { return smallestPivot_; }
  // x = (L D Lᵀ)⁻¹ b (x not b). Returns |T x − b| / |b| (0 when b = 0) for
  // T = (diagonal, upper) without the shift, summed in the back substitution's
  // pass, whose own recursion leaves time for it.
  double solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, const std::vector<double>& diagonal,
               const std::vector<double>& upper) const;
  // The same for the b given to row(), whose forward substitution is done.
  double backSubstitute(const Eigen::VectorXd& b, Eigen::VectorXd& x, const std::vector<double>& diagonal,
                        const std::vector<double>& upper) const;

 private:
  std::vector<double> inversePivot_, lower_, y_;  // 1/d_k, l_k; y_k of the rows given to row()
  double shift_ = 0.0, pivot_ = 0.0, forward_ = 0.0;  // μ; the last row's d_k and y_k
  double smallestPivot_ = 0.0;
  bool usable_ = true;
  // x = y on entry; x_{m−1} = y_{m−1} / d_{m−1}, x_k = y_k / d_k − l_k x_{k+1}; the residual as solve() says.
  double backward(const double* b, double* x, const double* diagonal, const double* upper) const;
};

}  // namespace particles::linear

#include "linear/tridiagonal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace particles::linear {

bool Tridiagonal::factorize(const std::vector<double>& diagonal, const std::vector<double>& upper, double shift) {
  const std::size_t m = diagonal.size();
  start(m, shift);
  for (std::size_t k = 0; k < m; ++k) row(k, diagonal[k], k > 0 ? upper[k - 1] : 0.0, 0.0);
  return usable_;
}

void Tridiagonal::start(std::size_t m, double shift) {
  inversePivot_.resize(m);
  y_.resize(m);
  lower_.resize(m > 0 ? m - 1 : 0);
  shift_ = shift;
  pivot_ = 0.0;
  smallestPivot_ = std::numeric_limits<double>::infinity();
  usable_ = true;
}

double Tridiagonal::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, const std::vector<double>& diagonal,
                          const std::vector<double>& upper) const {
  const Eigen::Index m = static_cast<Eigen::Index>(inversePivot_.size());
  x = b;
  double* y = x.data();
  const double* l = lower_.data();
  for (Eigen::Index k = 1; k < m; ++k) y[k] -= l[k - 1] * y[k - 1];
  return backward(b.data(), y, diagonal.data(), upper.data());
}

double Tridiagonal::backSubstitute(const Eigen::VectorXd& b, Eigen::VectorXd& x, const std::vector<double>& diagonal,
                                  const std::vector<double>& upper) const {
  x = Eigen::Map<const Eigen::VectorXd>(y_.data(), static_cast<Eigen::Index>(y_.size()));
  return backward(b.data(), x.data(), diagonal.data(), upper.data());
}

double Tridiagonal::backward(const double* b, double* x, const double* t, const double* u) const {
  const Eigen::Index m = static_cast<Eigen::Index>(inversePivot_.size());
  if (m == 0) return 0.0;
  const double *inverse = inversePivot_.data(), *l = lower_.data();
  double residual = 0.0, norm = 0.0;  // |T x − b|², |b|²
  // Row k's residual once x_{k−1}, x_k, x_{k+1} (0 past either end) are known.
  auto addResidual = [&](Eigen::Index k, double before, double at, double after) {
    const double r = (k > 0 ? u[k - 1] * before : 0.0) + t[k] * at + (k + 1 < m ? u[k] * after : 0.0) - b[k];
    residual += r * r;
    norm += b[k] * b[k];
  };
  // The recursion's values are carried in registers, not read back from x.
  double next = x[m - 1] * inverse[m - 1], afterNext = 0.0;  // x_{k+1}, x_{k+2}
  x[m - 1] = next;
  for (Eigen::Index k = m - 2; k >= 0; --k) {
    const double at = x[k] * inverse[k] - l[k] * next;
    x[k] = at;
    addResidual(k + 1, at, next, afterNext);
    afterNext = next;
    next = at;
  }
  addResidual(0, 0.0, next, afterNext);
  return norm == 0.0 ? 0.0 : std::sqrt(residual) / std::sqrt(norm);
}

}  // namespace particles::linear

#include "linear/tridiagonal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace particles::linear {

bool Tridiagonal::factorize(const std::vector<double>& diagonal, const std::vector<double>& upper, double shift) {
  const std::size_t m = diagonal.size();
  inversePivot_.resize(m);
  lower_.resize(m > 0 ? m - 1 : 0);
  const double *t = diagonal.data(), *u = upper.data();
  double *inverse = inversePivot_.data(), *l = lower_.data();
  bool usable = true;
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < m; ++k) {
    double d = t[k] + shift;
    if (k > 0) d -= l[k - 1] * u[k - 1];
    usable = usable && d != 0.0 && std::isfinite(d);
    smallest = std::min(smallest, d);
    inverse[k] = 1.0 / d;             // off the recursion's path
    if (k + 1 < m) l[k] = u[k] / d;   // on it: d_{k+1} waits for l_k
  }
  smallestPivot_ = smallest;
  return usable;
}

double Tridiagonal::smallestPivot() const { return smallestPivot_; }

void Tridiagonal::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const Eigen::Index m = static_cast<Eigen::Index>(inversePivot_.size());
  x = b;
  double* y = x.data();
  const double *inverse = inversePivot_.data(), *l = lower_.data();
  for (Eigen::Index k = 1; k < m; ++k) y[k] -= l[k - 1] * y[k - 1];
  if (m > 0) y[m - 1] *= inverse[m - 1];
  for (Eigen::Index k = m - 2; k >= 0; --k) y[k] = y[k] * inverse[k] - l[k] * y[k + 1];
}

double Tridiagonal::relativeResidual(const std::vector<double>& diagonal, const std::vector<double>& upper,
                                     const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  const Eigen::Index m = x.size();
  const double *t = diagonal.data(), *u = upper.data(), *in = x.data(), *rhs = b.data();
  double residual = 0.0, norm = 0.0;  // |T x − b|², |b|²
  for (Eigen::Index k = 0; k < m; ++k) {
    double r = t[k] * in[k];
    if (k > 0) r += u[k - 1] * in[k - 1];
    if (k + 1 < m) r += u[k] * in[k + 1];
    r -= rhs[k];
    residual += r * r;
    norm += rhs[k] * rhs[k];
  }
  return norm == 0.0 ? 0.0 : std::sqrt(residual) / std::sqrt(norm);
}

}  // namespace particles::linear

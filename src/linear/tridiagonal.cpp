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

void Tridiagonal::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const Eigen::Index m = static_cast<Eigen::Index>(inversePivot_.size());
  x = b;
  double* y = x.data();
  const double* l = lower_.data();
  for (Eigen::Index k = 1; k < m; ++k) y[k] -= l[k - 1] * y[k - 1];
  backSubstituteInPlace(y);
}

void Tridiagonal::backSubstitute(Eigen::VectorXd& x) const {
  x = Eigen::Map<const Eigen::VectorXd>(y_.data(), static_cast<Eigen::Index>(y_.size()));
  backSubstituteInPlace(x.data());
}

// x_{m−1} = y_{m−1} / d_{m−1},  x_k = y_k / d_k − l_k x_{k+1}, over y in place.
void Tridiagonal::backSubstituteInPlace(double* y) const {
  const Eigen::Index m = static_cast<Eigen::Index>(inversePivot_.size());
  const double *inverse = inversePivot_.data(), *l = lower_.data();
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

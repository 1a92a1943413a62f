#include "linear/tridiagonal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace particles::linear {

bool Tridiagonal::factorize(const std::vector<double>& diagonal, const std::vector<double>& upper, double shift) {
  const std::size_t m = diagonal.size();
  pivot_.resize(m);
  lower_.resize(m > 0 ? m - 1 : 0);
  bool usable = true;
  for (std::size_t k = 0; k < m; ++k) {
    double d = diagonal[k] + shift;
    if (k > 0) d -= lower_[k - 1] * upper[k - 1];
    pivot_[k] = d;
    usable = usable && d != 0.0 && std::isfinite(d);
    if (k + 1 < m) lower_[k] = upper[k] / d;
  }
  return usable;
}

double Tridiagonal::smallestPivot() const {
  return pivot_.empty() ? std::numeric_limits<double>::infinity() : *std::min_element(pivot_.begin(), pivot_.end());
}

void Tridiagonal::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
  const Eigen::Index m = static_cast<Eigen::Index>(pivot_.size());
  x = b;
  for (Eigen::Index k = 1; k < m; ++k) x[k] -= lower_[static_cast<std::size_t>(k - 1)] * x[k - 1];
  for (Eigen::Index k = m - 1; k >= 0; --k) {
    x[k] /= pivot_[static_cast<std::size_t>(k)];
    if (k + 1 < m) x[k] -= lower_[static_cast<std::size_t>(k)] * x[k + 1];
  }
}

void Tridiagonal::multiply(const std::vector<double>& diagonal, const std::vector<double>& upper,
                           const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const Eigen::Index m = x.size();
  y.resize(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    double sum = diagonal[static_cast<std::size_t>(k)] * x[k];
    if (k > 0) sum += upper[static_cast<std::size_t>(k - 1)] * x[k - 1];
    if (k + 1 < m) sum += upper[static_cast<std::size_t>(k)] * x[k + 1];
    y[k] = sum;
  }
}

}  // namespace particles::linear

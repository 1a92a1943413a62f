#pragma once
// Helpers shared by the unit tests: parameter-rejection checks, central finite
// differences, dense views of force contributions, and the log-log slope that
// every convergence-order test fits.
#include <cmath>
#include <cstddef>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "particles/constraint_solver.h"
#include "particles/force.h"
#include "particles/particle_system.h"

namespace test_support {

// Under ASan+UBSan (CI's second run) each case of a fuzz test costs about ten
// times as much: the fuzz tests take a share of their cases there.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitizerBuild = true;
#else
inline constexpr bool kSanitizerBuild = false;
#endif

// Least-squares slope of log y against log x: the order p of y ≈ C xᵖ
// (of a global error against dt, of an error against a tolerance). Over two
// points, the slope between them.
inline double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.size() != y.size() || x.size() < 2) throw std::invalid_argument("logLogSlope needs two or more (x, y) pairs");
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double lx = std::log(x[k]), ly = std::log(y[k]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// Records, at each of its evaluations, the CG iterations the solver reports
// then: forces are applied at the start of each derivative evaluation, when
// the solver still holds the statistics of the previous evaluation's solve.
// Adds no force; its Jacobians are exactly zero.
class CountingForce : public particles::Force {
 public:
  explicit CountingForce(const particles::ConstraintSolver& solver) : solver_(solver) {}
  const char* type() const override { return "counting"; }
  void apply(const particles::Phase&, Eigen::VectorXd&) const override { seen.push_back(solver_.stats().iterations); }
  bool hasJacobians() const override { return true; }
  void addJacobians(const particles::Phase&, particles::Triplets&, particles::Triplets&) const override {}
  mutable std::vector<int> seen;

 private:
  const particles::ConstraintSolver& solver_;
};

// Expects `action` to throw std::invalid_argument whose message contains `text`
// (the parameter's name, or the value it was given).
inline void expectRejected(const std::function<void()>& action, const std::string& text) {
  try {
    action();
    ADD_FAILURE() << "no std::invalid_argument thrown; expected one naming '" << text << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos)
        << "message '" << e.what() << "' does not name '" << text << "'";
  }
}

// ∂g/∂y by central differences, for a scalar g.
inline Eigen::VectorXd centralGradient(const std::function<double(const Eigen::VectorXd&)>& g,
                                       const Eigen::VectorXd& y, double h = 1e-6) {
  Eigen::VectorXd grad(y.size());
  for (int k = 0; k < y.size(); ++k) {
    Eigen::VectorXd yp = y, ym = y;
    yp[k] += h;
    ym[k] -= h;
    grad[k] = (g(yp) - g(ym)) / (2 * h);
  }
  return grad;
}

// ∂g/∂y by central differences, for a vector g (column k is ∂g/∂y_k).
inline Eigen::MatrixXd centralJacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& g, const Eigen::VectorXd& y,
    double h = 1e-6) {
  const Eigen::VectorXd g0 = g(y);
  Eigen::MatrixXd jac(g0.size(), y.size());
  for (int k = 0; k < y.size(); ++k) {
    Eigen::VectorXd yp = y, ym = y;
    yp[k] += h;
    ym[k] -= h;
    jac.col(k) = (g(yp) - g(ym)) / (2 * h);
  }
  return jac;
}

// The contribution of one force alone at phase s (2n).
inline Eigen::VectorXd forceAt(const particles::Force& force, const particles::Phase& s) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(s.x.size());
  force.apply(s, f);
  return f;
}

// Sums triplets (duplicates add) into a dense size × size matrix.
inline Eigen::MatrixXd denseFromTriplets(const particles::Triplets& triplets, int size) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(size, size);
  for (const auto& t : triplets) m(t.row(), t.col()) += t.value();
  return m;
}

// A vector of `size` entries drawn uniformly from [−1, 1].
inline Eigen::VectorXd randomVector(int size, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd y(size);
  for (int k = 0; k < size; ++k) y[k] = u(rng);
  return y;
}

// addJacobians against central differences of apply() in x and in v, at
// random positions and velocities of the system's particles.
inline void expectJacobiansMatchFiniteDifference(const particles::ParticleSystem& system,
                                                 const particles::Force& force, std::mt19937& rng,
                                                 int trials = 20) {
  ASSERT_TRUE(force.hasJacobians());
  const int size = 2 * system.size();
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::VectorXd x = randomVector(size, rng), v = randomVector(size, rng);
    particles::Triplets dfdxTriplets, dfdvTriplets;
    force.addJacobians(system.phase(x, v), dfdxTriplets, dfdvTriplets);
    const Eigen::MatrixXd dfdx = denseFromTriplets(dfdxTriplets, size);
    const Eigen::MatrixXd dfdv = denseFromTriplets(dfdvTriplets, size);
    const Eigen::MatrixXd fdx =
        centralJacobian([&](const Eigen::VectorXd& y) { return forceAt(force, system.phase(y, v)); }, x);
    const Eigen::MatrixXd fdv =
        centralJacobian([&](const Eigen::VectorXd& y) { return forceAt(force, system.phase(x, y)); }, v);
    EXPECT_LT((dfdx - fdx).norm(), 1e-6 * (1.0 + fdx.norm())) << "∂f/∂x\n" << dfdx << "\nFD\n" << fdx;
    EXPECT_LT((dfdv - fdv).norm(), 1e-6 * (1.0 + fdv.norm())) << "∂f/∂v\n" << dfdv << "\nFD\n" << fdv;
  }
}

}  // namespace test_support

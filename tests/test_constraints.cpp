// Finite-difference checks of every constraint kernel: J = ∂C/∂q and
// J̇ = dJ/dt along a velocity, at random configurations.
#include <random>

#include <gtest/gtest.h>

#include "particles/constraints/circular_wire.h"
#include "particles/constraints/line.h"
#include "particles/constraints/rod.h"
#include "particles/particle_system.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;
using test_support::expectRejected;

namespace {

// A constraint of N particles as a function of the stacked 2N positions and velocities.
template <int N>
using Kernel = std::function<ConstraintKernel<N>(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot)>;

template <int N>
void expectDerivativesMatchFiniteDifference(const Kernel<N>& kernel, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::VectorXd q(2 * N), qdot(2 * N);
    for (int k = 0; k < 2 * N; ++k) q[k] = u(rng), qdot[k] = u(rng);
    const ConstraintKernel<N> k0 = kernel(q, qdot);
    const double h = 1e-6;
    double cdotFromJ = 0.0;
    for (int p = 0; p < N; ++p) {
      cdotFromJ += k0.J[p].dot(qdot.segment<2>(2 * p));
      for (int axis = 0; axis < 2; ++axis) {
        Eigen::VectorXd qp = q, qm = q;
        qp[2 * p + axis] += h;
        qm[2 * p + axis] -= h;
        const double dC = (kernel(qp, qdot).C - kernel(qm, qdot).C) / (2 * h);
        EXPECT_NEAR(k0.J[p][axis], dC, 1e-6 * (1 + std::abs(dC))) << "J, particle " << p;
      }
      // J̇ = d/dt J(q + t q̇) at t = 0.
      const Vector2d dJ = (kernel(q + h * qdot, qdot).J[p] - kernel(q - h * qdot, qdot).J[p]) / (2 * h);
      EXPECT_NEAR((k0.Jdot[p] - dJ).norm(), 0.0, 1e-6 * (1 + dJ.norm())) << "J̇, particle " << p;
    }
    EXPECT_NEAR(k0.Cdot, cdotFromJ, 1e-12 * (1 + std::abs(cdotFromJ))) << "Ċ = J q̇";
  }
}

}  // namespace

TEST(CircularWireConstraint, JacobianAndTimeDerivativeMatchFiniteDifference) {
  std::mt19937 rng(1);
  const Vector2d centre(0.3, -0.2);
  expectDerivativesMatchFiniteDifference<1>(
      [&](const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
        return circularWireKernel(q.segment<2>(0), qd.segment<2>(0), centre, 0.7);
      },
      rng);
}

TEST(RodConstraint, SquaredFormDerivativesMatchFiniteDifference) {
  std::mt19937 rng(2);
  expectDerivativesMatchFiniteDifference<2>(
      [](const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
        return rodKernel(RodForm::Squared, q.segment<2>(0), q.segment<2>(2), qd.segment<2>(0),
                         qd.segment<2>(2), 0.4);
      },
      rng);
}

TEST(RodConstraint, RootFormDerivativesMatchFiniteDifference) {
  std::mt19937 rng(3);
  expectDerivativesMatchFiniteDifference<2>(
      [](const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
        return rodKernel(RodForm::Root, q.segment<2>(0), q.segment<2>(2), qd.segment<2>(0),
                         qd.segment<2>(2), 0.4);
      },
      rng);
}

TEST(RodConstraint, RootFormJdotWithoutTheRadialTermFailsTheCheck) {
  // The seed report's J̇ = ḋ/|d| omits −d(d·ḋ)/|d|³; show that the check would see it.
  const Vector2d xi(0.3, 0.1), xj(-0.2, 0.4), vi(0.5, -0.3), vj(-0.1, 0.2);
  const ConstraintKernel<2> k = rodKernel(RodForm::Root, xi, xj, vi, vj, 0.4);
  const Vector2d d = xi - xj, ddot = vi - vj;
  const Vector2d reportJdot = ddot / d.norm();
  EXPECT_GT((k.Jdot[0] - reportJdot).norm(), 1e-3);
}

TEST(LineConstraint, DerivativesMatchFiniteDifference) {
  std::mt19937 rng(4);
  expectDerivativesMatchFiniteDifference<1>(
      [](const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
        return lineKernel(q.segment<2>(0), qd.segment<2>(0), Vector2d(0.1, 0.5), 0.7);
      },
      rng);
}

TEST(LineConstraint, ZeroAngleIsTheHorizontalLineThroughThePoint) {
  const ConstraintKernel<1> k = lineKernel(Vector2d(3.0, 0.75), Vector2d::Zero(), Vector2d(0.0, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(k.C, 0.25);
}

TEST(RodConstraint, ViolationIsTheLengthErrorInBothForms) {
  ParticleSystem system;
  system.addParticle(Vector2d(0, 0), 1);
  system.addParticle(Vector2d(0.5, 0), 1);
  RodConstraint squared(0, 1, 0.4, RodForm::Squared), root(0, 1, 0.4, RodForm::Root);
  EXPECT_NEAR(squared.violation(system.phase()), 0.1, 1e-15);
  EXPECT_NEAR(root.violation(system.phase()), 0.1, 1e-15);
}

TEST(ConstraintParameters, RejectedWithTheirName) {
  expectRejected([] { RodConstraint(0, 1, 0.0); }, "rod length");
  expectRejected([] { RodConstraint(0, 1, -1.0); }, "rod length");
  expectRejected([] { RodConstraint(0, 1, std::nan("")); }, "rod length");
  expectRejected([] { RodConstraint(2, 2, 1.0); }, "itself");
  expectRejected([] { CircularWireConstraint(0, Vector2d::Zero(), 0.0); }, "wire radius");
  expectRejected([] { LineConstraint(0, Vector2d::Zero(), std::nan("")); }, "line angle");
  expectRejected([] { parseRodForm("cubed"); }, "rod form");
  ParticleSystem system;
  system.addParticle(Vector2d(0, 0), 1);
  expectRejected([&] { system.addConstraint(std::make_unique<RodConstraint>(0, 5, 1.0)); }, "particle 5");
}

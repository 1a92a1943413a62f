// Every force: equal and opposite where it should be, zero at its rest
// configuration, f = −∂E/∂x for the conservative ones, and the force
// Jacobians ∂f/∂x, ∂f/∂v against finite differences of apply().
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "particles/constants.h"
#include "particles/forces/angular_spring.h"
#include "particles/forces/drag.h"
#include "particles/forces/gravity.h"
#include "particles/forces/mouse_spring.h"
#include "particles/forces/spring.h"
#include "particles/particle_system.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;
using Eigen::VectorXd;
using test_support::centralGradient;
using test_support::centralJacobian;
using test_support::expectRejected;
using test_support::expectJacobiansMatchFiniteDifference;
using test_support::forceAt;
using test_support::randomVector;

namespace {

double cross(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// n particles with masses in [0.5, 2]; positions and velocities are drawn per trial.
ParticleSystem makeSystem(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> mass(0.5, 2.0);
  ParticleSystem system;
  for (int i = 0; i < n; ++i) system.addParticle(Vector2d::Zero(), mass(rng));
  return system;
}

// f(x, v) = −∂E/∂x at v = 0, for a force with a potential, at random positions.
void expectForceIsMinusEnergyGradient(const ParticleSystem& system, const Force& force,
                                      std::mt19937& rng, int trials = 30) {
  ASSERT_TRUE(force.hasPotential());
  const VectorXd v = VectorXd::Zero(2 * system.size());
  for (int trial = 0; trial < trials; ++trial) {
    const VectorXd x = randomVector(2 * system.size(), rng);
    const VectorXd f = forceAt(force, system.phase(x, v));
    const VectorXd grad = centralGradient(
        [&](const VectorXd& y) { return force.potential(system.phase(y, v)); }, x);
    EXPECT_LT((f + grad).norm(), 1e-6 * (1.0 + f.norm())) << "f = " << f.transpose()
                                                           << "\n−∂E/∂x = " << -grad.transpose();
  }
}

}  // namespace

// --- spring ------------------------------------------------------------------

TEST(SpringForce, ForcesAreEqualOppositeAndAlongTheSpring) {
  std::mt19937 rng(10);
  ParticleSystem system = makeSystem(3, rng);
  const SpringForce spring(0, 2, 0.4, 7.0, 1.5);
  for (int trial = 0; trial < 50; ++trial) {
    const VectorXd x = randomVector(6, rng), v = randomVector(6, rng);
    const VectorXd f = forceAt(spring, system.phase(x, v));
    const Vector2d l = x.segment<2>(0) - x.segment<2>(4);
    EXPECT_LT((f.segment<2>(0) + f.segment<2>(4)).norm(), 1e-12 * (1.0 + f.norm()));
    EXPECT_NEAR(cross(f.segment<2>(0), l), 0.0, 1e-12 * (1.0 + f.norm()));
    EXPECT_EQ(f.segment<2>(2), Vector2d::Zero()) << "particle 1 is not on the spring";
    EXPECT_GT(f.segment<2>(0).norm(), 0.0);
  }
}

TEST(SpringForce, ZeroAtRestLengthUnderRigidMotion) {
  std::mt19937 rng(11);
  ParticleSystem system = makeSystem(2, rng);
  const SpringForce spring(0, 1, 0.5, 7.0, 1.5);
  VectorXd x(4), v(4);
  x << 0.1, 0.2, 0.1 + 0.3, 0.2 + 0.4;  // |l| = 0.5
  v << 0.7, -0.3, 0.7, -0.3;            // common velocity: l̇ = 0
  EXPECT_LT(forceAt(spring, system.phase(x, v)).norm(), 1e-14);
}

TEST(SpringForce, StretchedSpringPullsTheEndsTogether) {
  std::mt19937 rng(12);
  ParticleSystem system = makeSystem(2, rng);
  const SpringForce spring(0, 1, 0.5, 4.0, 0.0);
  VectorXd x(4), v = VectorXd::Zero(4);
  x << 1.0, 0.0, 0.0, 0.0;  // |l| = 1, stretched by 0.5
  const VectorXd f = forceAt(spring, system.phase(x, v));
  EXPECT_NEAR(f[0], -2.0, 1e-14);  // −k_s (|l| − r) toward particle 1
  EXPECT_NEAR(f[2], 2.0, 1e-14);
}

TEST(SpringForce, ForceIsMinusEnergyGradient) {
  std::mt19937 rng(13);
  ParticleSystem system = makeSystem(3, rng);
  const SpringForce spring(2, 0, 0.6, 5.0, 2.0);
  expectForceIsMinusEnergyGradient(system, spring, rng);
}

// The damping term is k_d (l̇·l)/|l| along l (the seed report's k_d l/|l| is a typo):
// a purely tangential relative velocity is not damped at all.
TEST(SpringForce, TangentialRelativeVelocityGivesNoDampingForce) {
  std::mt19937 rng(14);
  ParticleSystem system = makeSystem(2, rng);
  const SpringForce spring(0, 1, 0.5, 4.0, 3.0);
  VectorXd x(4), v(4);
  x << 0.5, 0.0, 0.0, 0.0;  // at rest length, along x
  v << 0.0, 2.0, 0.0, -1.0;  // relative velocity along y only
  EXPECT_LT(forceAt(spring, system.phase(x, v)).norm(), 1e-14);
}

TEST(SpringForce, DampingIsKdTimesTheStretchRateAlongTheSpring) {
  std::mt19937 rng(15);
  ParticleSystem system = makeSystem(2, rng);
  const double kd = 3.0;
  const SpringForce spring(0, 1, 0.5, 4.0, kd);
  VectorXd x(4), v(4);
  x << 0.3, 0.4, 0.0, 0.0;   // |l| = 0.5 = r, u = (0.6, 0.8)
  v << 1.0, 2.0, 0.0, 0.5;   // l̇ = (1, 1.5), l̇·u = 1.8
  const VectorXd f = forceAt(spring, system.phase(x, v));
  EXPECT_LT((f.segment<2>(0) - (-kd * 1.8) * Vector2d(0.6, 0.8)).norm(), 1e-13);
}

TEST(SpringForce, JacobiansMatchFiniteDifference) {
  std::mt19937 rng(16);
  ParticleSystem system = makeSystem(3, rng);
  const SpringForce spring(1, 2, 0.4, 6.0, 1.2);
  expectJacobiansMatchFiniteDifference(system, spring, rng);
}

// --- angular spring -----------------------------------------------------------

TEST(AngularSpringForce, ForcesSumToZeroAndExertNoNetTorque) {
  std::mt19937 rng(20);
  ParticleSystem system = makeSystem(4, rng);
  const AngularSpringForce spring(3, 0, 1, 1.1, 2.5, 0.7);
  for (int trial = 0; trial < 50; ++trial) {
    const VectorXd x = randomVector(8, rng), v = randomVector(8, rng);
    const VectorXd f = forceAt(spring, system.phase(x, v));
    Vector2d total = Vector2d::Zero();
    double torque = 0.0;
    for (int i = 0; i < 4; ++i) {
      total += f.segment<2>(2 * i);
      torque += cross(x.segment<2>(2 * i), f.segment<2>(2 * i));
    }
    EXPECT_LT(total.norm(), 1e-10 * (1.0 + f.norm()));
    EXPECT_NEAR(torque, 0.0, 1e-10 * (1.0 + f.norm()));
    EXPECT_EQ(f.segment<2>(4), Vector2d::Zero()) << "particle 2 is not in the triple";
  }
}

TEST(AngularSpringForce, ZeroAtRestAngleUnderRigidMotion) {
  std::mt19937 rng(21);
  ParticleSystem system = makeSystem(3, rng);
  const double rest = 2.0;
  const AngularSpringForce spring(0, 1, 2, rest, 3.0, 1.0);
  // Vertex at (0.2, −0.1); arms of lengths 0.5 and 0.8 at angles 0.3 and 0.3 + θ₀.
  const Vector2d vertex(0.2, -0.1);
  const Vector2d a = 0.5 * Vector2d(std::cos(0.3), std::sin(0.3));
  const Vector2d b = 0.8 * Vector2d(std::cos(0.3 + rest), std::sin(0.3 + rest));
  VectorXd x(6), v(6);
  x << vertex + a, vertex, vertex + b;
  // Rigid rotation about the vertex at rate ω plus a translation: θ̇ = 0.
  const double omega = 1.7;
  const Vector2d drift(0.4, -0.2);
  auto rotate = [&](const Vector2d& r) { return Vector2d(drift + omega * Vector2d(-r.y(), r.x())); };
  v << rotate(a), drift, rotate(b);
  EXPECT_LT(forceAt(spring, system.phase(x, v)).norm(), 1e-12);
}

TEST(AngularSpringForce, ForceIsMinusEnergyGradient) {
  std::mt19937 rng(22);
  ParticleSystem system = makeSystem(3, rng);
  // θ₀ = 0.5: random triples stay away from θ − θ₀ = ±π, where E has a kink.
  const AngularSpringForce spring(0, 1, 2, 0.5, 2.0, 0.8);
  const VectorXd v = VectorXd::Zero(6);
  int checked = 0;
  for (int trial = 0; checked < 30; ++trial) {
    const VectorXd x = randomVector(6, rng);
    const Vector2d a = x.segment<2>(0) - x.segment<2>(2), b = x.segment<2>(4) - x.segment<2>(2);
    const double theta = std::atan2(cross(a, b), a.dot(b));
    if (std::abs(angleDifference(theta, 0.5)) > 0.9 * particles::kPi || a.norm() < 0.1 || b.norm() < 0.1)
      continue;
    const VectorXd f = forceAt(spring, system.phase(x, v));
    const VectorXd grad = centralGradient(
        [&](const VectorXd& y) { return spring.potential(system.phase(y, v)); }, x, 1e-7);
    EXPECT_LT((f + grad).norm(), 1e-6 * (1.0 + f.norm()));
    ++checked;
  }
}

// With k_s = 0 the power of the forces is Σ f_k·v_k = −k_d θ̇².
TEST(AngularSpringForce, DampingDissipatesAtRateKdThetaDotSquared) {
  std::mt19937 rng(23);
  ParticleSystem system = makeSystem(3, rng);
  const double kd = 0.9;
  const AngularSpringForce spring(0, 1, 2, 0.5, 0.0, kd);
  for (int trial = 0; trial < 30; ++trial) {
    const VectorXd x = randomVector(6, rng), v = randomVector(6, rng);
    const VectorXd f = forceAt(spring, system.phase(x, v));
    // θ̇ by a central difference of θ along v.
    auto angle = [&](const VectorXd& y) {
      const Vector2d a = y.segment<2>(0) - y.segment<2>(2), b = y.segment<2>(4) - y.segment<2>(2);
      return std::atan2(cross(a, b), a.dot(b));
    };
    const double h = 1e-7;
    const double rate = angleDifference(angle(x + h * v), angle(x - h * v)) / (2 * h);
    EXPECT_NEAR(f.dot(v), -kd * rate * rate, 1e-5 * (1.0 + rate * rate));
  }
}

// --- gravity, mouse spring, drag ----------------------------------------------

TEST(GravityForce, IsMassTimesGOnMovableParticlesAndMinusEnergyGradient) {
  std::mt19937 rng(30);
  ParticleSystem system = makeSystem(3, rng);
  system.setPinned(1, true);
  const Vector2d g(0.5, -9.81);
  const GravityForce gravity(g);
  const VectorXd f = forceAt(gravity, system.phase());
  EXPECT_LT((f.segment<2>(0) - system.masses()[0] * g).norm(), 1e-14);
  EXPECT_EQ(f.segment<2>(2), Vector2d::Zero()) << "a pinned particle feels no gravity";
  EXPECT_LT((f.segment<2>(4) - system.masses()[2] * g).norm(), 1e-14);
  expectForceIsMinusEnergyGradient(system, gravity, rng, 5);
}

TEST(GravityForce, JacobiansMatchFiniteDifference) {
  std::mt19937 rng(31);
  ParticleSystem system = makeSystem(2, rng);
  expectJacobiansMatchFiniteDifference(system, GravityForce(Vector2d(0.0, -9.81)), rng, 3);
}

TEST(MouseSpringForce, ZeroAtTheTargetAndActsOnItsParticleOnly) {
  std::mt19937 rng(40);
  ParticleSystem system = makeSystem(3, rng);
  const Vector2d target(0.3, -0.7);
  MouseSpringForce mouse(1, target, 20.0, 2.0);
  system.setPosition(1, target);
  EXPECT_LT(forceAt(mouse, system.phase()).norm(), 1e-14);
  system.setPosition(1, target + Vector2d(0.1, 0.0));
  const VectorXd f = forceAt(mouse, system.phase());
  EXPECT_NEAR(f[2], -2.0, 1e-12);  // −k_s (x − t), toward the target
  EXPECT_EQ(f.segment<2>(0), Vector2d::Zero());
  EXPECT_EQ(f.segment<2>(4), Vector2d::Zero());
}

TEST(MouseSpringForce, ForceIsMinusEnergyGradient) {
  std::mt19937 rng(41);
  ParticleSystem system = makeSystem(3, rng);
  const MouseSpringForce mouse(2, Vector2d(0.2, 0.1), 15.0, 3.0);
  expectForceIsMinusEnergyGradient(system, mouse, rng);
}

TEST(MouseSpringForce, JacobiansMatchFiniteDifference) {
  std::mt19937 rng(42);
  ParticleSystem system = makeSystem(3, rng);
  const MouseSpringForce mouse(0, Vector2d(-0.4, 0.3), 15.0, 3.0);
  expectJacobiansMatchFiniteDifference(system, mouse, rng);
}

TEST(DragForce, ZeroAtRestAndOpposesVelocityOfMovableParticles) {
  std::mt19937 rng(50);
  ParticleSystem system = makeSystem(2, rng);
  const DragForce drag(0.8);
  EXPECT_EQ(forceAt(drag, system.phase()), VectorXd::Zero(4));
  system.setPinned(0, true);
  VectorXd v(4);
  v << 1.0, 2.0, -0.5, 0.25;
  const VectorXd f = forceAt(drag, system.phase(system.positions(), v));
  EXPECT_EQ(f.segment<2>(0), Vector2d::Zero()) << "no drag on a pinned particle";
  EXPECT_LT((f.segment<2>(2) + 0.8 * v.segment<2>(2)).norm(), 1e-15);
}

TEST(DragForce, JacobiansMatchFiniteDifference) {
  std::mt19937 rng(51);
  ParticleSystem system = makeSystem(3, rng);
  system.setPinned(1, true);
  expectJacobiansMatchFiniteDifference(system, DragForce(0.6), rng);
}

// --- parameters ---------------------------------------------------------------

TEST(ForceParameters, RejectedWithTheirName) {
  const double nan = std::nan("");
  expectRejected([] { SpringForce(0, 1, 0.0, 1.0, 0.0); }, "spring rest length");
  expectRejected([] { SpringForce(0, 1, -0.5, 1.0, 0.0); }, "spring rest length");
  expectRejected([&] { SpringForce(0, 1, nan, 1.0, 0.0); }, "spring rest length");
  expectRejected([] { SpringForce(0, 1, 1.0, -1.0, 0.0); }, "spring stiffness");
  expectRejected([] { SpringForce(0, 1, 1.0, 1.0, -1.0); }, "spring damping");
  expectRejected([] { SpringForce(3, 3, 1.0, 1.0, 0.0); }, "itself");
  expectRejected([&] { AngularSpringForce(0, 1, 2, nan, 1.0, 0.0); }, "angular spring rest angle");
  expectRejected([] { AngularSpringForce(0, 1, 2, 1.0, -1.0, 0.0); }, "angular spring stiffness");
  expectRejected([] { AngularSpringForce(0, 1, 2, 1.0, 1.0, -1.0); }, "angular spring damping");
  expectRejected([] { AngularSpringForce(0, 1, 0, 1.0, 1.0, 0.0); }, "three distinct particles");
  expectRejected([&] { MouseSpringForce(0, Vector2d(nan, 0.0), 1.0, 0.0); }, "mouse target.x");
  expectRejected([] { MouseSpringForce(0, Vector2d::Zero(), -1.0, 0.0); }, "mouse spring stiffness");
  expectRejected([] { MouseSpringForce(0, Vector2d::Zero(), 1.0, -2.0); }, "mouse spring damping");
  expectRejected([] { DragForce(-0.1); }, "drag damping");
  expectRejected([&] { GravityForce(Vector2d(0.0, nan)); }, "gravity.y");
}

// The wind force: the edge kernel's pressure law and its Jacobians, gusts
// that repeat, the clock sampled once per step, and a particle blown on its
// spring to the closed-form steady state under every integrator.
#include <cmath>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "particles/constants.h"
#include "particles/forces/drag.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/forces/wind.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;
using Eigen::VectorXd;
using test_support::expectRejected;
using test_support::forceAt;

namespace {

WindSettings breeze(double speed, double direction, double drag) {
  WindSettings w;
  w.speed = speed;
  w.direction = direction;
  w.drag = drag;
  return w;
}

}  // namespace

TEST(WindEdgeForce, AnEdgeAcrossTheWindTakesItsFullPressureAlongItsNormal) {
  // A 0.5 m edge along x in a 3 m/s wind blowing up (+y), c = 0.2:
  // F = c |d| u_n² n = 0.2 · 0.5 · 9 = 0.9 N, upward, whichever way the edge runs.
  const Vector2d up(0.0, 3.0);
  for (const Vector2d& d : {Vector2d(0.5, 0.0), Vector2d(-0.5, 0.0)}) {
    const Vector2d F = windEdgeForce(d, up, 0.2);
    EXPECT_NEAR(F.x(), 0.0, 1e-15);
    EXPECT_NEAR(F.y(), 0.9, 1e-12);
  }
  // Along the wind: no pressure. At 30° to it (60° from x): u_n = 3 sin 30°, F = 0.2 · 0.5 · 1.5².
  EXPECT_EQ(windEdgeForce(Vector2d(0.0, 0.5), up, 0.2).norm(), 0.0);
  const Vector2d slanted(0.5 * std::cos(particles::kPi / 3), 0.5 * std::sin(particles::kPi / 3));
  EXPECT_NEAR(windEdgeForce(slanted, up, 0.2).norm(), 0.2 * 0.5 * 1.5 * 1.5, 1e-12);
  // An edge of length 0 takes none.
  EXPECT_EQ(windEdgeForce(Vector2d::Zero(), up, 0.2).norm(), 0.0);
}

TEST(WindForce, EachEndTakesHalfAndTheEdgesOwnMotionCounts) {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 0.0), 1.0);
  system.addParticle(Vector2d(0.4, 0.0), 1.0);
  const WindForce wind({{0, 1}}, breeze(2.0, particles::kPi / 2, 0.5));  // 2 m/s upward
  VectorXd f = forceAt(wind, system.phase());
  // 0.5 · 0.4 · 2² = 0.8 N on the edge, 0.4 N on each end.
  EXPECT_NEAR(f[1], 0.4, 1e-12);
  EXPECT_NEAR(f[3], 0.4, 1e-12);
  EXPECT_NEAR(f[0], 0.0, 1e-15);
  // The edge rising at the wind's speed feels no wind at all.
  system.setVelocities((Eigen::VectorXd(4) << 0.0, 2.0, 0.0, 2.0).finished());
  EXPECT_LT(forceAt(wind, system.phase()).norm(), 1e-15);
  // Rising twice as fast, it is pushed down by the still air as hard as it was pushed up.
  system.setVelocities((Eigen::VectorXd(4) << 0.0, 4.0, 0.0, 4.0).finished());
  f = forceAt(wind, system.phase());
  EXPECT_NEAR(f[1], -0.4, 1e-12);
  EXPECT_NEAR(f[3], -0.4, 1e-12);
}

TEST(WindForce, JacobiansMatchFiniteDifference) {
  std::mt19937 rng(7);
  ParticleSystem system;
  for (int i = 0; i < 4; ++i) system.addParticle(Vector2d::Zero(), 1.0);
  WindSettings w = breeze(1.3, 0.7, 0.4);
  w.gust = 0.5;
  const WindForce wind({{0, 1}, {1, 2}, {3, 1}, {2, 3}}, w);
  test_support::expectJacobiansMatchFiniteDifference(system, wind, rng);
}

TEST(WindForce, DefiniteJacobiansAreTheExactVelocityPartNegativeSemiDefinite) {
  std::mt19937 rng(11);
  ParticleSystem system;
  for (int i = 0; i < 3; ++i) system.addParticle(Vector2d::Zero(), 1.0);
  const WindForce wind({{0, 1}, {1, 2}}, breeze(2.0, -0.4, 0.3));
  for (int trial = 0; trial < 20; ++trial) {
    const VectorXd x = test_support::randomVector(6, rng), v = test_support::randomVector(6, rng);
    Triplets exactX, exactV, definiteX, definiteV;
    wind.addJacobians(system.phase(x, v), exactX, exactV);
    wind.addDefiniteJacobians(system.phase(x, v), definiteX, definiteV);
    EXPECT_TRUE(definiteX.empty());
    const Eigen::MatrixXd dv = test_support::denseFromTriplets(definiteV, 6);
    EXPECT_EQ((dv - test_support::denseFromTriplets(exactV, 6)).norm(), 0.0);
    EXPECT_LT((dv - dv.transpose()).norm(), 1e-15);
    EXPECT_LT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dv).eigenvalues().maxCoeff(), 1e-12);
  }
}

TEST(WindSettings, BadValuesAreRejectedNamingTheField) {
  const auto make = [](WindSettings w) { WindForce({{0, 1}}, w); };
  WindSettings w;
  w.speed = -1.0;
  expectRejected([&] { make(w); }, "wind speed");
  w = WindSettings{};
  w.gust = 1.5;
  expectRejected([&] { make(w); }, "wind gust");
  w = WindSettings{};
  w.gustPeriod = 0.0;
  expectRejected([&] { make(w); }, "wind gust period");
  w = WindSettings{};
  w.drag = std::nan("");
  expectRejected([&] { make(w); }, "wind drag");
  w = WindSettings{};
  w.seed = -3;
  expectRejected([&] { make(w); }, "wind seed");
  expectRejected([] { WindForce({{2, 2}}, WindSettings{}); }, "itself");
}

TEST(Gusts, RepeatForOneSeedDifferForAnotherAndStayWithinTheirAmplitude) {
  WindSettings w = breeze(4.0, 0.0, 0.1);
  w.gust = 0.5;
  w.gustPeriod = 2.0;
  double lowest = 1e9, highest = 0.0, mean = 0.0, seedsDiffer = 0.0;
  const int samples = 20000;
  for (int k = 0; k < samples; ++k) {
    const double t = 0.01 * k;  // 200 s, a hundred slowest periods
    const double speed = airVelocity(w, t).norm();
    EXPECT_EQ(speed, airVelocity(w, t).norm());
    lowest = std::min(lowest, speed);
    highest = std::max(highest, speed);
    mean += speed / samples;
    WindSettings other = w;
    other.seed = 2;
    seedsDiffer = std::max(seedsDiffer, std::abs(airVelocity(other, t).norm() - speed));
    EXPECT_NEAR(airVelocity(w, t).y(), 0.0, 1e-15);
  }
  // (1 − A) U = 2 and (1 + A) U = 6 bound the speed; the gusts reach most of that range.
  EXPECT_GE(lowest, 2.0);
  EXPECT_LE(highest, 6.0);
  EXPECT_LT(lowest, 2.6);
  EXPECT_GT(highest, 5.4);
  EXPECT_NEAR(mean, 4.0, 0.05);
  EXPECT_GT(seedsDiffer, 1.0);
}

TEST(WindForce, TheAirIsSampledOnceAtTheStartOfEveryStep) {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 0.0), 1.0);
  system.addParticle(Vector2d(0.0, -0.1), 1.0);
  system.setPinned(0, true);
  WindSettings w = breeze(3.0, 0.0, 0.05);
  w.gust = 0.8;
  w.gustPeriod = 0.5;
  const auto& wind = static_cast<const WindForce&>(system.addForce(std::make_unique<WindForce>(
      std::vector<std::array<int, 2>>{{0, 1}}, w)));
  const auto rk4 = makeIntegrator("rk4");
  const Snapshot start = system.snapshot();
  for (int k = 0; k < 50; ++k) {
    const double t = system.time();
    system.step(*rk4, 0.01);
    EXPECT_EQ(wind.air(), airVelocity(w, t)) << "step " << k;  // held over the step from its start
  }
  // Restoring the clock samples the air there.
  system.restore(start);
  EXPECT_EQ(wind.air(), airVelocity(w, 0.0));
}

// A particle of mass m on a spring (rest r, stiffness k) from a pin, the
// spring itself the edge the wind (speed U along +x, drag c) blows on.
// Blown out to angle θ from hanging straight, with length L:
//   across the spring: the particle's half of the edge's force balances gravity,
//     ½ c L U² cos²θ = m g sin θ   →   sin θ = (√(a² + 4) − a)/2,  a = 2 m g/(c L U²);
//   along it: k (L − r) = m g cos θ.
// Every integrator must come to rest there (drag settles it and vanishes at rest).
TEST(WindForce, BlowsAParticleOnASpringToItsClosedFormSteadyStateUnderEveryIntegrator) {
  const double m = 0.1, r = 0.5, k = 200.0, g = 9.81, c = 0.1, U = 4.0;
  double L = r, sine = 0.0;
  for (int pass = 0; pass < 100; ++pass) {
    const double a = 2.0 * m * g / (c * L * U * U);
    sine = 0.5 * (std::sqrt(a * a + 4.0) - a);
    L = r + m * g * std::sqrt(1.0 - sine * sine) / k;
  }
  const double theta = std::asin(sine);
  ASSERT_NEAR(theta, 0.364, 0.01);  // about 21°: a real lean, not a rounding

  for (const IntegratorInfo& info : integratorTable()) {
    SCOPED_TRACE(info.name);
    ParticleSystem system;
    system.addParticle(Vector2d(0.0, 0.0), m);
    system.addParticle(Vector2d(0.0, -r), m);
    system.setPinned(0, true);
    system.addForce(std::make_unique<SpringForce>(0, 1, r, k, 2.0));
    system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -g)));
    system.addForce(std::make_unique<DragForce>(0.3));
    system.addForce(std::make_unique<WindForce>(std::vector<std::array<int, 2>>{{0, 1}}, breeze(U, 0.0, c)));
    // dopri5 at a tight tolerance: at its default 2e-5 its step control keeps
    // the particle trembling by ~1e-6 m about the steady state.
    IntegratorSettings settings;
    settings.dopri5.tolerance = 1e-10;
    const auto integrator = makeIntegrator(info.name, settings);
    for (int step = 0; step < 7500; ++step) {  // 15 s: settled to rounding
      const StepStats stats = system.step(*integrator, 0.002);
      ASSERT_EQ(stats.failure, StepFailure::None);
    }
    const Vector2d x = system.position(1);
    EXPECT_NEAR(std::atan2(x.x(), -x.y()), theta, 1e-8);
    EXPECT_NEAR(x.norm(), L, 1e-10);
    EXPECT_LT(system.velocity(1).norm(), 1e-8);
  }
}

// dopri5 (Dormand–Prince 5(4)): a global error that follows its tolerance
// (its fifth order on fixed steps is measured with every scheme's in
// test_integrators), FSAL (six evaluations per accepted step), the
// internal step carried between calls and never cut at an output time (dense
// output), and the floor, work cap and tolerance
// limits every adaptive scheme shares; contacts that restart the internal
// solution without freezing it (a bounce, a slide).
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "particles/collider.h"
#include "particles/constraints/circular_wire.h"
#include "particles/forces/gravity.h"
#include "integrators/dopri5.h"
#include "particles/particle_system.h"
#include "particles/threads.h"
#include "bench/cloth_grid.h"
#include "bench/rod_chain.h"
#include "oscillator_fixture.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

// The oscillator at ω = 2 rad/s (a period of π s), swinging ±0.5 about its
// rest length of 1.
test_support::Oscillator oscillator() {
  test_support::Oscillator o;
  o.params.stiffness = 4.0;
  o.params.stretch = 0.5;
  return o;
}

}  // namespace

namespace {

// One step of h of the Dormand–Prince tableau (HNW I, Table II.5.2) written
// plainly: each stage's point y₀ + h Σ a_sj k_j summed by Eigen's whole
// vectors, y₀ first and then each nonzero term in turn, and its
// accelerations by ParticleSystem::acceleration, one evaluation at a time.
void plainDormandPrinceStep(ParticleSystem& system, double h) {
  const double a[7][6] = {{0.0},
                          {1.0 / 5.0},
                          {3.0 / 40.0, 9.0 / 40.0},
                          {44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0},
                          {19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0},
                          {9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0},
                          {35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0}};
  const Eigen::VectorXd x0 = system.positions(), v0 = system.velocities();
  std::vector<Eigen::VectorXd> kx(7), kv(7);
  kx[0] = v0;
  system.acceleration(x0, v0, kv[0]);
  Eigen::VectorXd x;
  for (int s = 1; s < 7; ++s) {
    x = x0;
    kx[s] = v0;
    for (int j = 0; j < s; ++j) {
      if (a[s][j] == 0.0) continue;
      x += (h * a[s][j]) * kx[j];
      kx[s] += (h * a[s][j]) * kv[j];
    }
    system.acceleration(x, kx[s], kv[s]);
  }
  system.setPositions(x);
  system.setVelocities(kx[6]);
}

}  // namespace

// A fixed step takes the same step as the tableau written plainly, to the
// bit: on a 72×72 cloth of springs, gravity and drag on one and two threads
// (its force passes parallel), and on a rod chain (a constraint solve
// between the forces and a).
TEST(Dopri5, AFixedStepIsTheTableauWrittenPlainlyBitForBit) {
  IntegratorSettings fixed;
  fixed.dopri5.adaptive = false;
  const double h = 2e-3;
  for (const int threads : {1, 2}) {
    particles::setThreadCount(threads);
    ParticleSystem fused = bench::clothGrid(72, 72, 0.05), plain = bench::clothGrid(72, 72, 0.05);
    fused.threadUse().adaptive = false;
    auto dopri5 = makeIntegrator("dopri5", fixed);
    for (int k = 0; k < 3; ++k) {
      fused.step(*dopri5, h);
      plainDormandPrinceStep(plain, h);
    }
    EXPECT_TRUE(fused.positions() == plain.positions()) << threads << " threads";
    EXPECT_TRUE(fused.velocities() == plain.velocities()) << threads << " threads";
    EXPECT_GT((fused.positions() - bench::clothGrid(72, 72, 0.05).positions()).norm(), 0.0) << "the cloth moved";
  }
  particles::setThreadCount(1);
  ParticleSystem fused = bench::horizontalRodChain(12, 0.1), plain = bench::horizontalRodChain(12, 0.1);
  auto dopri5 = makeIntegrator("dopri5", fixed);
  for (int k = 0; k < 3; ++k) {
    fused.step(*dopri5, h);
    plainDormandPrinceStep(plain, h);
  }
  EXPECT_TRUE(fused.positions() == plain.positions());
  EXPECT_TRUE(fused.velocities() == plain.velocities());
}

TEST(Dopri5, GlobalErrorFallsSteadilyWithTheTolerance) {
  const test_support::Oscillator o = oscillator();
  std::vector<double> tolerances, errors;
  for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
    IntegratorSettings settings;
    settings.dopri5.tolerance = tol;
    ParticleSystem system = o.build();
    auto dopri5 = makeIntegrator("dopri5", settings);
    double worst = 0.0;
    // 10 s (~3 periods) in output intervals of 1 s, longer than the loosest
    // tolerance's steps: the tolerance alone sets the internal step.
    for (int k = 0; k < 10; ++k) {
      const StepStats stats = system.step(*dopri5, 1.0);
      ASSERT_EQ(stats.failure, StepFailure::None);
      worst = std::max(worst, o.error(system));
    }
    tolerances.push_back(tol);
    errors.push_back(worst);
    RecordProperty("error_at_tolerance_" + std::to_string(tol), std::to_string(worst));
  }
  for (std::size_t k = 1; k < errors.size(); ++k)
    EXPECT_LT(errors[k], errors[k - 1]) << "tolerance " << tolerances[k];
  EXPECT_LT(errors.back(), 1e-3 * errors.front());  // six decades of tolerance, well over one of error
  EXPECT_GT(test_support::logLogSlope(tolerances, errors), 0.6);  // error ∝ tol^(5/6) for a fifth-order pair in theory
}

TEST(Dopri5, SixEvaluationsPerStepAndTheInternalStepCarriesOverCalls) {
  IntegratorSettings settings;
  settings.dopri5.tolerance = 1e-8;
  const test_support::Oscillator o = oscillator();
  ParticleSystem system = o.build();
  Dopri5Integrator dopri5;
  dopri5.configure(settings);
  system.step(dopri5, 1.0);  // the first call also evaluates k₁ and the starting-step probe
  for (int k = 0; k < 5; ++k) {
    const StepStats stats = system.step(dopri5, 1.0);
    EXPECT_GT(stats.internalSteps, 5);  // dt is the output interval, not the step
    EXPECT_EQ(stats.forceEvaluations, 6 * (stats.internalSteps + stats.rejectedSteps));  // FSAL
  }
  // Output intervals far shorter than the internal step: no step is cut at
  // an output time. Most calls fall inside the last accepted step and
  // evaluate nothing; their states come from the dense output and follow the
  // closed form as closely as the states on the internal grid.
  const double h = dopri5.internalStep();
  ASSERT_GT(h, 0.01);
  double gridError = 0.0;
  for (int k = 0; k < 5; ++k) {
    system.step(dopri5, 1.0);
    gridError = std::max(gridError, o.error(system));
  }
  int steps = 0, rejected = 0, evaluations = 0, emptyCalls = 0;
  double denseError = 0.0;
  const int calls = 500;
  for (int k = 0; k < calls; ++k) {
    const StepStats stats = system.step(dopri5, 0.001);
    steps += stats.internalSteps;
    rejected += stats.rejectedSteps;
    evaluations += stats.forceEvaluations;
    if (stats.internalSteps == 0) {
      ++emptyCalls;
      EXPECT_EQ(stats.forceEvaluations, 0);
    }
    denseError = std::max(denseError, o.error(system));
  }
  EXPECT_EQ(evaluations, 6 * (steps + rejected));  // FSAL across calls too
  EXPECT_LE(steps, static_cast<int>(calls * 0.001 / (0.5 * h)) + 1) << "internal step " << h;
  EXPECT_GT(emptyCalls, calls / 2);
  EXPECT_LT(denseError, 10.0 * gridError + 1e-9) << "on the grid " << gridError;
}

// The default tolerance is chosen for the scenes' dt of 0.01 (integrator.h):
// on bench_step's 80-rod chain released horizontally, called every 0.01 s
// for 0.35 s, dopri5 must end closer to a reference (RK4 at dt 2·10⁻⁵,
// another scheme) than RK4 at dt 0.01 does, and by a clear margin, with
// hardly a rejected step and about one internal step per call once started (the
// first 0.05 s include the starting step's search).
TEST(Dopri5, TheDefaultToleranceBeatsRk4AtTheScenesStep) {
  const double T = 0.35;
  auto endPositions = [&](const std::string& name, double dt, StepStats* work) {
    ParticleSystem system = bench::horizontalRodChain(80, 0.05);
    auto integrator = makeIntegrator(name);
    const int steps = static_cast<int>(std::lround(T / dt));
    for (int k = 0; k < steps; ++k) {
      const StepStats stats = system.step(*integrator, dt);
      if (k * dt >= 0.05 - 1e-12) *work += stats;  // after the first 0.05 s, as bench_step times it
    }
    return Eigen::VectorXd(system.positions());
  };
  StepStats referenceWork, rk4Work, dopri5Work;
  dopri5Work.internalSteps = 0;
  const Eigen::VectorXd reference = endPositions("rk4", 2e-5, &referenceWork);
  const double rk4Error = (endPositions("rk4", 0.01, &rk4Work) - reference).cwiseAbs().maxCoeff();
  const double dopri5Error = (endPositions("dopri5", 0.01, &dopri5Work) - reference).cwiseAbs().maxCoeff();
  RecordProperty("rk4_error", std::to_string(rk4Error));
  RecordProperty("dopri5_error", std::to_string(dopri5Error));
  std::cout << "80-rod chain, T = " << T << " s, dt 0.01: RK4 error " << rk4Error << ", dopri5 at tolerance "
            << IntegratorSettings{}.dopri5.tolerance << " error " << dopri5Error << " (" << rk4Error / dopri5Error
            << "x closer), " << dopri5Work.internalSteps << " internal steps (" << dopri5Work.rejectedSteps
            << " rejected) in the last 30 calls\n";
  EXPECT_LT(dopri5Error, rk4Error / 3.0);
  EXPECT_LE(dopri5Work.rejectedSteps, 2);
  EXPECT_LE(dopri5Work.internalSteps, 33);
}

TEST(AdaptiveSchemes, RefuseTolerancesDoublePrecisionCannotMeet) {
  for (const IntegratorInfo& info : integratorTable()) {
    if (!info.usesTolerance) continue;
    IntegratorSettings settings;
    settings.dopri5.tolerance = 1e-25;
    test_support::expectRejected([&] { makeIntegrator(info.name, settings); }, "integrator tolerance must be >=");
  }
}

// A bead held on two circular wires that do not meet: no state satisfies both,
// and the constraint forces fight at every step. An adaptive scheme must give
// up within its floor and work cap and say so, not take forever.
TEST(AdaptiveSchemes, ConflictingWiresEndACallWithAReportedFailure) {
  for (const IntegratorInfo& info : integratorTable()) {
    if (!info.usesTolerance) continue;
    ParticleSystem system;
    system.addParticle(Vector2d(0.5, 0.0), 1.0, Vector2d(0.0, 0.3));
    system.addConstraint(std::make_unique<CircularWireConstraint>(0, Vector2d(0.0, 0.0), 0.5));
    system.addConstraint(std::make_unique<CircularWireConstraint>(0, Vector2d(1.2, 0.0), 0.5));
    system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
    IntegratorSettings settings;
    settings.dopri5.tolerance = 1e-10;
    settings.dopri5.maxStepsPerCall = 2000;
    auto integrator = makeIntegrator(info.name, settings);
    StepFailure failure = StepFailure::None;
    for (int k = 0; k < 200 && failure == StepFailure::None; ++k) {
      const StepStats stats = system.step(*integrator, 0.01);
      failure = stats.failure;
      EXPECT_LE(stats.internalSteps + stats.rejectedSteps, settings.dopri5.maxStepsPerCall) << info.name;
    }
    EXPECT_NE(failure, StepFailure::None) << info.name;
    EXPECT_TRUE(system.finite()) << info.name;
  }
}

TEST(AdaptiveSchemes, TheWorkCapEndsACallThatNeedsMoreSteps) {
  for (const IntegratorInfo& info : integratorTable()) {
    if (!info.usesTolerance) continue;
    IntegratorSettings settings;
    settings.dopri5.tolerance = 1e-10;
    settings.dopri5.maxStepsPerCall = 10;
    ParticleSystem system = oscillator().build();
    auto integrator = makeIntegrator(info.name, settings);
    const StepStats stats = system.step(*integrator, 100.0);  // ~30 periods in one call
    EXPECT_EQ(stats.failure, StepFailure::WorkCapReached) << info.name;
    EXPECT_LE(stats.internalSteps + stats.rejectedSteps, 10) << info.name;
  }
}

namespace {

// A unit mass dropped from rest at height 1 m onto a floor y = 0 of restitution 1.
ParticleSystem elasticDrop() {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 1.0), 1.0);
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  Collider floor = Collider::halfPlane(Vector2d::Zero(), Vector2d(0.0, 1.0));
  floor.restitution = 1.0;
  system.addCollider(floor);
  return system;
}

}  // namespace

// Every bounce restarts the internal solution; the restarted step must not be
// the controller's proposal, which uniform gravity grows tenfold per step
// until dense output rounds back to the old state and the ball freezes (it
// froze at y 0.017 m from t 12.9 s). Over 30 s (16 bounces) the energy stays
// within 1% and the height follows RK4 at dt 10⁻⁴ to 10⁻⁶ m: one ball on a
// floor is not chaotic, and both schemes integrate the parabola exactly.
TEST(Dopri5, ElasticBounceKeepsItsEnergyAndFollowsRk4) {
  const double dt = 0.01, referenceDt = 1e-4, T = 30.0;
  ParticleSystem bounce = elasticDrop(), reference = elasticDrop();
  auto dopri5 = makeIntegrator("dopri5");
  auto rk4 = makeIntegrator("rk4");
  const double e0 = bounce.totalEnergy();
  const int steps = static_cast<int>(std::lround(T / dt)), substeps = static_cast<int>(std::lround(dt / referenceDt));
  double worstEnergy = 0.0, worstHeight = 0.0;
  for (int k = 0; k < steps; ++k) {
    bounce.step(*dopri5, dt);
    for (int j = 0; j < substeps; ++j) reference.step(*rk4, referenceDt);
    worstEnergy = std::max(worstEnergy, std::abs(bounce.totalEnergy() - e0) / std::abs(e0));
    worstHeight = std::max(worstHeight, std::abs(bounce.position(0).y() - reference.position(0).y()));
  }
  EXPECT_LT(worstEnergy, 0.01) << "relative energy error " << worstEnergy;
  EXPECT_LT(worstHeight, 1e-6) << "largest height difference from RK4 at dt 1e-4: " << worstHeight << " m";
}

// A particle at rest on a 35° slope with μ 0.5 (friction angle 26.6°) is in
// contact at every step, so every step restarts the internal solution. It
// slides the Coulomb distance ½ a t² = 3.218 m in 2 s, a = g (sin θ − μ cos θ),
// plus the a t dt/2 = 16 mm of the contact solve's first-order position
// update (x = x_ref + h v for a held particle) — (before the restart step was
// bounded it moved 0.024 m).
TEST(Dopri5, SlidesTheCoulombDistanceDownASlope) {
  const double g = 9.81, mu = 0.5, dt = 0.01, T = 2.0, angle = 35.0 * M_PI / 180.0;
  const Vector2d normal(-std::sin(angle), std::cos(angle)), along(std::cos(angle), std::sin(angle));
  ParticleSystem system;
  const Vector2d start = 2.0 * along;
  system.addParticle(start, 1.0);
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -g)));
  Collider slope = Collider::halfPlane(Vector2d::Zero(), normal);
  slope.friction = mu;
  system.addCollider(slope);
  auto dopri5 = makeIntegrator("dopri5");
  for (int k = 0; k < static_cast<int>(std::lround(T / dt)); ++k) system.step(*dopri5, dt);
  const double moved = along.dot(start - system.position(0));
  const double a = g * (std::sin(angle) - mu * std::cos(angle)), coulomb = 0.5 * a * T * T + 0.5 * a * T * dt;
  EXPECT_NEAR(moved, coulomb, 1e-6 * coulomb) << "moved " << moved << " m of " << coulomb << " m";
}

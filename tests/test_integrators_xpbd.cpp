// XPBD against closed forms and the force-based schemes: the static stretch of
// a compliant spring, hard rods held after the substeps, the energy removed by
// the damping term, first-order position error, and a user's force without a
// position form applied in the prediction.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "particles/collider.h"
#include "particles/constraints/rod.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "integrators/xpbd.h"
#include "particles/particle_system.h"
#include "particles/threads.h"
#include "xpbd/distance.h"
#include "xpbd/distance_blocks.h"
#include "scenes/cloth.h"
#include "oscillator_fixture.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

IntegratorSettings xpbdSettings(int substeps, int iterations) {
  IntegratorSettings settings;
  settings.xpbd.substeps = substeps;
  settings.xpbd.iterations = iterations;
  return settings;
}

std::unique_ptr<Integrator> xpbd(int substeps, int iterations) {
  return makeIntegrator("xpbd", xpbdSettings(substeps, iterations));
}

// Particle 1 (mass m) on a spring of rest length r below particle 0, pinned.
ParticleSystem hangingSpring(double mass, double stiffness, double damping, double g) {
  ParticleSystem system;
  system.addParticle(Vector2d::Zero(), 1.0);
  system.addParticle(Vector2d(0.0, -1.0), mass);
  system.setPinned(0, true);
  system.addForce(std::make_unique<SpringForce>(0, 1, 1.0, stiffness, damping));
  if (g != 0.0) system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -g)));
  return system;
}

// A horizontal chain of `links` rods of length r from a pinned end, under gravity.
ParticleSystem rodChain(int links, double r, RodForm form) {
  ParticleSystem system;
  for (int i = 0; i <= links; ++i) system.addParticle(Vector2d(r * i, 0.0), 1.0);
  system.setPinned(0, true);
  for (int i = 0; i < links; ++i) system.addConstraint(std::make_unique<RodConstraint>(i, i + 1, r, form));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
  return system;
}

// A user's own force type, unknown to xpbd's table: a steady push F on every
// particle.
class SteadyPush : public Force {
 public:
  explicit SteadyPush(Eigen::Vector2d push) : push_(push) {}
  const char* type() const override { return "steady-push"; }
  void apply(const Phase& s, Eigen::VectorXd& f) const override {
    for (Eigen::Index i = 0; i < s.x.size() / 2; ++i) f.segment<2>(2 * i) += push_;
  }

 private:
  Eigen::Vector2d push_;
};

// An n×n 8-way grid of compliant, damped springs 0.1 apart, particles row by row.
std::vector<CompliantDistance> compliantGrid(int n) {
  std::vector<CompliantDistance> springs;
  auto id = [&](int r, int c) { return r * n + c; };
  auto add = [&](int a, int b, double rest) {
    CompliantDistance d;
    d.i = a;
    d.j = b;
    d.rest = rest;
    d.compliance = springCompliance(1e3, 0.5, 1e-3);
    springs.push_back(d);
  };
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      if (c + 1 < n) add(id(r, c), id(r, c + 1), 0.1);
      if (r + 1 < n) add(id(r, c), id(r + 1, c), 0.1);
      if (r + 1 < n && c + 1 < n) add(id(r, c), id(r + 1, c + 1), 0.1 * std::sqrt(2.0));
      if (r + 1 < n && c + 1 < n) add(id(r, c + 1), id(r + 1, c), 0.1 * std::sqrt(2.0));
    }
  return springs;
}

}  // namespace

TEST(DistanceBatch, ProjectionOfAStretchedHardSpringRestoresItsLength) {
  // α = 0 (infinitely stiff): one projection puts |d| = r, split by inverse mass.
  CompliantDistance c;
  c.i = 0;
  c.j = 1;
  c.rest = 1.0;
  DistanceBatch batch;
  batch.build({c}, Eigen::Vector2d(1.0, 3.0));
  double x[4] = {0.0, 0.0, 1.4, 0.0};
  const double xn[4] = {0.0, 0.0, 1.4, 0.0};
  batch.project(xn, x, 0, 2);
  EXPECT_NEAR(x[2] - x[0], 1.0, 1e-15);
  EXPECT_NEAR(x[0], 0.1, 1e-15);  // w_i/(w_i + w_j) of the 0.4 excess
  EXPECT_NEAR(x[2], 1.1, 1e-15);
  EXPECT_NEAR(batch.multiplier(0), -0.1, 1e-15);
}

TEST(DistanceBatch, ColouredPassEqualsTheSerialGaussSeidelPassInItsOrder) {
  // A 12×12 8-way grid of compliant, damped springs, randomly stretched: the
  // batch's pass (strided runs as vector loops, the rest in blocks whose
  // lengths are taken together) must give the positions of one-by-one
  // projections in the batch's order. Rebuilt one constraint at a time in
  // that order, the serial pass is a batch of one constraint per step; both
  // are Gauss–Seidel in the same order only if no run or block reads a
  // position another constraint of it moved. Pinned particles and two rest
  // lengths give runs of several entries.
  const int n = 12;
  std::vector<CompliantDistance> springs = compliantGrid(n);
  auto id = [&](int r, int c) { return r * n + c; };
  springs[7].rest = 0.12;  // a run of another entry inside the first row's
  Eigen::VectorXd w = Eigen::VectorXd::Constant(n * n, 2.0), xn(2 * n * n);
  w[0] = w[5] = 0.0;  // pinned
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) xn.segment<2>(2 * id(r, c)) = Eigen::Vector2d(0.1 * c, -0.1 * r);
  Eigen::VectorXd x = xn + 0.02 * Eigen::VectorXd::Random(2 * n * n);
  x.segment<2>(0) = xn.segment<2>(0);
  x.segment<2>(10) = xn.segment<2>(10);
  DistanceBatch batch;
  batch.build(springs, w);
  ASSERT_GT(batch.colours(), 3u);
  ASSERT_GT(batch.runs(), 10u);
  ASSERT_GT(batch.constraintsInRuns(), springs.size() / 2) << "most of the grid in strided runs";
  ASSERT_LT(batch.constraintsInRuns(), springs.size()) << "and some constraints left to the blocks";
  for (int passes : {1, 3}) {
    Eigen::VectorXd batched = x, serial = x;
    for (int pass = 0; pass < passes; ++pass) batch.project(xn.data(), batched.data(), pass, passes);
    std::vector<DistanceBatch> ones(springs.size());
    for (int pass = 0; pass < passes; ++pass)
      for (int k : batch.order()) {
        if (pass == 0) ones[k].build({springs[k]}, w);
        ones[k].project(xn.data(), serial.data(), pass, passes);
      }
    EXPECT_LT((batched - x).norm(), 1.0);  // moved, and not blown up
    EXPECT_GT((batched - x).norm(), 1e-3);
    for (int k = 0; k < 2 * n * n; ++k) ASSERT_EQ(batched[k], serial[k]) << passes << " passes, coordinate " << k;
  }
}

// The blocks' pass (xpbd/distance_blocks.h) is the one-by-one Gauss–Seidel
// pass in the order it reports, with the multipliers it reports, on one
// thread and on two (where the blocks are shared out and the cuts run in
// parallel): a 40×40 8-way grid cut into blocks of two rows, with ties
// between far particles left to the rest.
// Constraints with both particles in one block of B particles: the blocks'
// share, which must reach kParallelConstraints for a pass to run its blocks
// on several threads.
std::size_t inBlocks(const std::vector<CompliantDistance>& springs, int B) {
  return static_cast<std::size_t>(std::count_if(springs.begin(), springs.end(),
                                                [&](const CompliantDistance& c) { return c.i / B == c.j / B; }));
}

TEST(DistanceBlocks, PassEqualsTheSerialGaussSeidelPassInItsOrderOnAnyThreadCount) {
  const int n = 48;
  std::vector<CompliantDistance> springs = compliantGrid(n);
  auto id = [&](int r, int c) { return r * n + c; };
  for (int k = 0; k < 30; ++k) {  // far apart: the rest
    CompliantDistance tie = springs.front();
    tie.i = id(k, 0);
    tie.j = id(n - 1 - k, n - 1);
    tie.rest = 3.0;
    springs.push_back(tie);
  }
  Eigen::VectorXd w = Eigen::VectorXd::Constant(n * n, 2.0), xn(2 * n * n);
  w[0] = 0.0;  // pinned
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) xn.segment<2>(2 * id(r, c)) = Vector2d(0.1 * c, -0.1 * r);
  Eigen::VectorXd x = xn + 0.02 * Eigen::VectorXd::Random(2 * n * n);
  x.segment<2>(0) = xn.segment<2>(0);
  DistanceBlocks blocks;
  blocks.build(springs, w, 2 * n);
  ASSERT_EQ(blocks.blocks(), 24u);
  ASSERT_EQ(blocks.cuts(), 23u);
  ASSERT_GE(inBlocks(springs, 2 * n), particles::kParallelConstraints);  // the blocks run on the threads
  ASSERT_GE(blocks.rest(), 20u);
  ASSERT_EQ(blocks.size(), springs.size());
  std::vector<int> sorted = blocks.order();
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < sorted.size(); ++k) ASSERT_EQ(sorted[k], static_cast<int>(k)) << "each constraint once";
  for (int threads : {1, 2})
    for (int passes : {1, 3}) {
      SCOPED_TRACE(testing::Message() << threads << " threads, " << passes << " passes");
      setThreadCount(threads);
      Eigen::VectorXd blocked = x, serial = x;
      for (int pass = 0; pass < passes; ++pass) blocks.project(xn.data(), blocked.data(), pass, passes);
      setThreadCount(1);
      std::vector<DistanceBatch> ones(springs.size());
      for (int pass = 0; pass < passes; ++pass)
        for (int k : blocks.order()) {
          if (pass == 0) ones[k].build({springs[k]}, w);
          ones[k].project(xn.data(), serial.data(), pass, passes);
        }
      EXPECT_GT((blocked - x).norm(), 1e-3);  // moved
      for (int k = 0; k < 2 * n * n; ++k) ASSERT_EQ(blocked[k], serial[k]) << "coordinate " << k;
      if (passes > 1) {
        for (std::size_t k = 0; k < blocks.size(); ++k)
          ASSERT_EQ(blocks.multiplier(k), ones[blocks.order()[k]].multiplier(0)) << "constraint " << k;
      }
    }
}

// project()'s after(begin, end) runs once on every particle, after the last constraint on it: the
// positions it sees are the pass's final ones, the same as a pass with no after gives. With every constraint in a block or a cut it runs in
// the blocks' region (on the threads that projected them); with far ties in the rest, after the rest.
TEST(DistanceBlocks, AfterSeesEveryParticleOnceAtItsFinalPosition) {
  const int n = 48;
  for (const bool ties : {false, true})
    for (const int threads : {1, 2}) {
      SCOPED_TRACE(testing::Message() << threads << " threads, ties " << ties);
      std::vector<CompliantDistance> springs = compliantGrid(n);
      for (int k = 0; ties && k < 30; ++k) {
        CompliantDistance tie = springs.front();
        tie.i = k * n;
        tie.j = (n - 1 - k) * n + n - 1;
        tie.rest = 3.0;
        springs.push_back(tie);
      }
      Eigen::VectorXd w = Eigen::VectorXd::Constant(n * n, 2.0), xn(2 * n * n);
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) xn.segment<2>(2 * (r * n + c)) = Vector2d(0.1 * c, -0.1 * r);
      Eigen::VectorXd x = xn + 0.02 * Eigen::VectorXd::Random(2 * n * n);
      DistanceBlocks blocks;
      blocks.build(springs, w, 2 * n);
      ASSERT_EQ(blocks.rest() > 0, ties);
      ASSERT_GE(inBlocks(springs, 2 * n), particles::kParallelConstraints);
      setThreadCount(threads);
      Eigen::VectorXd seen = Eigen::VectorXd::Constant(2 * n * n, std::numeric_limits<double>::quiet_NaN());
      std::vector<std::atomic<int>> calls(static_cast<std::size_t>(n * n));
      for (auto& c : calls) c = 0;
      const Eigen::VectorXd start = x;
      blocks.project(xn.data(), x.data(), 0, 1, {}, [&](int begin, int end) {
        for (int i = begin; i < end; ++i) {
          ++calls[static_cast<std::size_t>(i)];
          seen.segment<2>(2 * i) = x.segment<2>(2 * i);
        }
      });
      DistanceBlocks without;  // the same pass with no after: the same positions
      without.build(springs, w, 2 * n);
      Eigen::VectorXd plain = start;
      without.project(xn.data(), plain.data(), 0, 1);
      setThreadCount(1);
      EXPECT_GT((x - start).norm(), 1e-3);  // moved
      for (int i = 0; i < n * n; ++i) {
        ASSERT_EQ(x[2 * i], plain[2 * i]) << "particle " << i;
        ASSERT_EQ(x[2 * i + 1], plain[2 * i + 1]) << "particle " << i;
        ASSERT_EQ(calls[static_cast<std::size_t>(i)].load(), 1) << "particle " << i;
        ASSERT_EQ(seen[2 * i], x[2 * i]) << "particle " << i;
        ASSERT_EQ(seen[2 * i + 1], x[2 * i + 1]) << "particle " << i;
      }
    }
}

TEST(Xpbd, CompliantSpringSettlesAtTheStaticStretch) {
  const double mass = 0.5, stiffness = 200.0, g = 9.8;
  for (auto [substeps, iterations] : {std::pair{1, 1}, std::pair{20, 1}, std::pair{4, 5}}) {
    SCOPED_TRACE(testing::Message() << substeps << " x " << iterations);
    ParticleSystem system = hangingSpring(mass, stiffness, 4.0, g);
    auto integrator = xpbd(substeps, iterations);
    for (int k = 0; k < 60 * 30; ++k) system.step(*integrator, 1.0 / 60.0);
    const double stretch = -system.position(1).y() - 1.0;
    EXPECT_NEAR(stretch, mass * g / stiffness, 1e-6 * mass * g / stiffness);
    EXPECT_LT(system.velocity(1).norm(), 1e-6);
  }
}

TEST(Xpbd, ZeroComplianceRodsHoldAfterTheSubsteps) {
  const double r = 0.1;
  // One rod: each projection is exact, so every substep ends on |d| = r.
  for (RodForm form : {RodForm::Root, RodForm::Squared}) {
    SCOPED_TRACE(rodFormName(form));
    ParticleSystem pendulum = rodChain(1, r, form);
    auto integrator = makeIntegrator("xpbd");
    for (int k = 0; k < 120; ++k) {
      pendulum.step(*integrator, 1.0 / 60.0);
      ASSERT_LE(pendulum.maxConstraintError(), 1e-6 * r) << "step " << k;
    }
  }
  // A chain couples its rods, and Gauss–Seidel passes converge linearly: three
  // rods need tens of passes per substep for 1e-6 r (ten rods at 20 × 1 stay
  // near 5e-3 r: the report's small-steps section measures it).
  auto worstOverASecond = [&](int substeps, int iterations) {
    ParticleSystem chain = rodChain(3, r, RodForm::Root);
    auto integrator = xpbd(substeps, iterations);
    double worst = 0.0, lowest = 0.0;
    for (int k = 0; k < 60; ++k) {
      chain.step(*integrator, 1.0 / 60.0);
      worst = std::max(worst, chain.maxConstraintError());
      lowest = std::min(lowest, chain.position(3).y());
    }
    EXPECT_LT(lowest, -0.2);  // the chain swung down: the rods held while it moved
    return worst;
  };
  const double onePass = worstOverASecond(50, 1), tenPasses = worstOverASecond(50, 10),
               fortyPasses = worstOverASecond(50, 40);
  EXPECT_LE(fortyPasses, 1e-6 * r);
  EXPECT_LT(fortyPasses, tenPasses);
  EXPECT_LT(tenPasses, onePass);
}

TEST(Xpbd, DampingRemovesTheEnergyOfTheDampedSpring) {
  // The oscillator (m = 1, ω = 2π) with a damper, released 0.2 beyond its
  // rest length. The force-based reference (RK4 at dt = 1e-4) gives the
  // energy the damper removes over T; XPBD at a small h must remove the same.
  const double damping = 0.8, T = 2.0;
  auto build = [&](double kd) {
    test_support::Oscillator oscillator;
    oscillator.params.damping = kd;
    oscillator.params.stretch = 0.2;
    return oscillator.build();
  };
  ParticleSystem reference = build(damping);
  const double e0 = reference.totalEnergy();
  auto rk4 = makeIntegrator("rk4");
  for (int k = 0; k < 20000; ++k) reference.step(*rk4, T / 20000);
  const double lostReference = e0 - reference.totalEnergy();
  ASSERT_GT(lostReference, 0.5 * e0);  // the damper does real work

  ParticleSystem damped = build(damping), undamped = build(0.0);
  auto integrator = xpbd(50, 1);
  for (int k = 0; k < 200; ++k) {
    damped.step(*integrator, T / 200);
    undamped.step(*integrator, T / 200);
  }
  const double lost = e0 - damped.totalEnergy(), lostNumerically = e0 - undamped.totalEnergy();
  EXPECT_NEAR(lost, lostReference, 0.02 * lostReference);
  // Without k_d the same steps lose little: the loss above is the damping term's.
  EXPECT_LT(lostNumerically, 0.05 * lostReference);
}

TEST(Xpbd, PositionErrorIsFirstOrderInTheSubstep) {
  // The undamped oscillator (ω = 2π, ±0.1 about r = 1) at 10 substeps of one
  // pass: h = dt/10, so the slope against dt is the slope against h.
  const test_support::OrderFit fit =
      test_support::Oscillator().measureOrder("xpbd", 1.3, {100, 200, 400, 800}, xpbdSettings(10, 1));
  EXPECT_NEAR(fit.order, 1.0, 0.15) << fit.errors.front() << " to " << fit.errors.back();
}

TEST(Xpbd, AppliesAUserForceWithoutAPositionFormInThePrediction) {
  // A free particle of mass m pushed by F from rest: x = F t²/(2m). The
  // prediction's symplectic Euler substeps of h give F/m h² N(N+1)/2 after N
  // of them, F t h/(2m) ahead of the closed form.
  const double m = 2.0, F = 3.0, dt = 0.01, T = 1.0;
  const int substeps = 20;
  ParticleSystem system;
  system.addParticle(Vector2d::Zero(), m);
  system.addForce(std::make_unique<SteadyPush>(Vector2d(F, 0.0)));
  auto integrator = xpbd(substeps, 1);
  const int steps = static_cast<int>(std::lround(T / dt));
  for (int k = 0; k < steps; ++k) system.step(*integrator, dt);
  const double h = dt / substeps, N = steps * substeps;
  EXPECT_NEAR(system.position(0).x(), F / m * h * h * N * (N + 1) / 2.0, 1e-12);
  EXPECT_NEAR(system.position(0).x(), F * T * T / (2.0 * m), F * T * h / (2.0 * m) * 1.01);
  EXPECT_NEAR(system.velocity(0).x(), F * T / m, 1e-9);  // (x − xⁿ)/h: rounding of 1e5 substeps
  EXPECT_EQ(system.position(0).y(), 0.0);
}

TEST(Xpbd, SettingsAreValidatedNamingTheField) {
  IntegratorSettings bad;
  bad.xpbd.substeps = 0;
  test_support::expectRejected([&] { makeIntegrator("xpbd", bad); }, "substeps");
  bad = IntegratorSettings{};
  bad.xpbd.iterations = -3;
  test_support::expectRejected([&] { makeIntegrator("xpbd", bad); }, "iterations");
  // A refused configuration leaves the integrator's settings as they were.
  XpbdIntegrator direct;
  bad = IntegratorSettings{};
  bad.xpbd.substeps = 7;
  direct.configure(bad);
  bad.xpbd.substeps = 0;
  test_support::expectRejected([&] { direct.configure(bad); }, "substeps");
  EXPECT_EQ(direct.settings().substeps, 7);
}

// The declared ranges are what validation enforces, at both ends (the
// command line, the scene file and the panel read the same ranges).
TEST(Xpbd, TheDeclaredRangesAreTheValidatedOnes) {
  for (const auto& [range, field] : {std::pair{XpbdSettings::substepRange, &XpbdSettings::substeps},
                                     std::pair{XpbdSettings::iterationRange, &XpbdSettings::iterations}}) {
    XpbdSettings s;
    for (const int inside : {range.min, range.max}) {
      s.*field = inside;
      EXPECT_NO_THROW(s.validate()) << inside;
    }
    for (const int outside : {range.min - 1, range.max + 1}) {
      s.*field = outside;
      EXPECT_THROW(s.validate(), std::invalid_argument) << outside;
    }
  }
}

TEST(Xpbd, ReportsTheSubstepAsItsInternalStep) {
  ParticleSystem system = hangingSpring(1.0, 10.0, 0.0, 9.8);
  auto integrator = xpbd(8, 2);
  system.step(*integrator, 0.04);
  EXPECT_DOUBLE_EQ(integrator->lastInternalStep(), 0.005);
}

TEST(Xpbd, DroppedParticleBouncesOnTheFloorInsideTheSubstepsAsRk4Does) {
  // Dropped from 1 m onto a box floor (top at y = 0, e = 0.8) at 1/60 s steps.
  // RK4 with the step's contact pass meets the floor at the exact time of
  // impact on its (exact) parabola, so its rebound apex is e² × 1 m. xpbd with
  // 20 substeps resolves the contact inside the substep it happens in: the
  // particle must never be below the floor by more than the contact slop
  // (1e-9 m), must bounce in the same steps as RK4 and reach its
  // apexes within 1 % (the substeps are first order: about g h per apex).
  struct Bounce {
    std::vector<double> times, apexes;
    double lowest = 0.0;
    int contacts = 0;
  };
  const double dt = 1.0 / 60.0, e = 0.8;
  auto drop = [&](Integrator& integrator) {
    ParticleSystem s;
    s.addParticle(Vector2d(0.0, 1.0), 1.0);
    s.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
    Collider floor = Collider::box(Vector2d(-100.0, -1.0), Vector2d(100.0, 0.0));
    floor.restitution = e;
    s.addCollider(floor);
    Bounce b;
    double apex = 0.0;
    for (int k = 0; k < 150; ++k) {  // 2.5 s: three bounces
      const double before = s.velocity(0).y();
      s.step(integrator, dt);
      b.lowest = std::min(b.lowest, s.position(0).y());
      b.contacts += s.contactsLastStep();
      apex = std::max(apex, s.position(0).y());
      if (before < 0.0 && s.velocity(0).y() > 0.0) {
        b.times.push_back(s.time());
        apex = 0.0;
      }
      if (before > 0.0 && s.velocity(0).y() <= 0.0) b.apexes.push_back(apex);
    }
    return b;
  };
  auto rk4 = makeIntegrator("rk4");
  auto substeps = xpbd(20, 1);
  const Bounce reference = drop(*rk4), small = drop(*substeps);
  ASSERT_GE(reference.times.size(), 3u);
  ASSERT_EQ(small.times.size(), reference.times.size());
  ASSERT_EQ(small.apexes.size(), reference.apexes.size());
  // The yardstick itself: e² × 1 m, sampled at the steps' ends (g dt²/8 off at most).
  EXPECT_NEAR(reference.apexes[0], e * e, 9.8 * dt * dt / 8);
  EXPECT_GE(small.lowest, -1e-9);
  EXPECT_GE(small.contacts, static_cast<int>(small.times.size()));
  for (std::size_t k = 0; k < small.times.size(); ++k) {
    EXPECT_NEAR(small.times[k], reference.times[k], dt / 2) << "bounce " << k;
    EXPECT_NEAR(small.apexes[k], reference.apexes[k], 0.01 * reference.apexes[k]) << "apex " << k;
  }
}

TEST(Xpbd, StiffClothAt60HzKeepsEverySpringWithinThreePercent) {
  // The 128×128 8-way cloth at k_s = 4e5 under g = 9.8, its top row on a rail,
  // 30 substeps of one pass per 1/60 s frame: the setting that
  // bench_stiff_cloth times within 16 ms a frame. Gauss–Seidel leaves the
  // cloth softer than k_s: with 20 substeps the worst spring passes 3 %.
  // Every frame of the first 1.5 s, then every tenth to 6 s: with the springs
  // cut into blocks of 8 rows (xpbd/distance_blocks.h) the cloth passed 6 %
  // at 3.3 s and 38 % at 5 s.
  scenes::Scene scene = scenes::buildCloth(scenes::stiffClothParams(128));
  auto integrator = xpbd(30, 1);
  double worst = 0.0;
  for (int frame = 0; frame < 360; ++frame) {
    scene.system->step(*integrator, 1.0 / 60.0);
    if (frame >= 90 && frame % 10 != 9) continue;
    for (const auto& force : scene.system->forceObjects()) {
      const auto* spring = dynamic_cast<const SpringForce*>(force.get());
      if (spring == nullptr) continue;
      worst = std::max(worst, std::abs(spring->strain(scene.system->positions())));
    }
  }
  EXPECT_LE(worst, 0.03);
  EXPECT_GT(worst, 0.002);  // the cloth is loaded: the bound is not met by standing still
}

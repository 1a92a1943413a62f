// StepStats: what a step reports is what it did — force evaluations and
// constraint solves counted independently by a force that watches the solver,
// CG iterations summed over the step, failures of a solve reported; and the
// divergence test (particles/divergence.h), each reason on its own.
#include <cmath>
#include <limits>

#include <stdexcept>

#include <gtest/gtest.h>

#include "particles/constraints/rod.h"
#include "particles/divergence.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/particle_system.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

// A chain of four rods hanging from a pinned particle, released sideways, with gravity.
ParticleSystem makeChain() {
  ParticleSystem system;
  for (int i = 0; i < 5; ++i) system.addParticle(Vector2d(0.1 * i, 0.0), 1.0);
  system.setPinned(0, true);
  for (int i = 0; i < 4; ++i) system.addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  return system;
}

// Force evaluations per step of each explicit scheme on smooth motion.
struct Expected {
  const char* name;
  int evaluations;
};

}  // namespace

TEST(StepStats, ExplicitSchemesCountEveryEvaluationAndSumCgIterationsOverTheStep) {
  for (const Expected& e : {Expected{"euler", 1}, Expected{"symplectic-euler", 1}, Expected{"midpoint", 2},
                            Expected{"rk4", 4}}) {
    ParticleSystem system = makeChain();
    system.solver().settings.method = SolveMethod::ConjugateGradient;
    system.solver().settings.warmStart = false;
    auto& counter = static_cast<test_support::CountingForce&>(system.addForce(std::make_unique<test_support::CountingForce>(system.solver())));
    auto integrator = makeIntegrator(e.name);
    for (int step = 0; step < 3; ++step) {
      counter.seen.clear();
      const StepStats stats = system.step(*integrator, 0.005);
      ASSERT_EQ(static_cast<int>(counter.seen.size()), e.evaluations) << e.name;
      // Solves 1 … k−1 were seen by evaluations 2 … k; solve k is the solver's last.
      int iterations = system.lastSolve().iterations;
      for (std::size_t k = 1; k < counter.seen.size(); ++k) iterations += counter.seen[k];
      EXPECT_EQ(stats.forceEvaluations, e.evaluations) << e.name;
      EXPECT_EQ(stats.solves, e.evaluations) << e.name;  // one constraint solve per evaluation
      EXPECT_EQ(stats.cgIterations, iterations) << e.name;
      EXPECT_GT(stats.cgIterations, system.lastSolve().iterations * (e.evaluations > 1 ? 1 : 0)) << e.name;
      EXPECT_EQ(stats.internalSteps, 1) << e.name;
      EXPECT_EQ(stats.rejectedSteps, 0) << e.name;
      EXPECT_EQ(stats.failure, StepFailure::None) << e.name;
      EXPECT_EQ(system.lastStepStats().cgIterations, stats.cgIterations);
    }
  }
}

TEST(StepStats, EveryIntegratorReportsItsForceEvaluations) {
  for (const IntegratorInfo& info : integratorTable()) {
    ParticleSystem system = makeChain();
    auto& counter = static_cast<test_support::CountingForce&>(system.addForce(std::make_unique<test_support::CountingForce>(system.solver())));
    auto integrator = info.make();
    // xpbd applies a force without a position form once per substep, as its
    // forceEvaluations count (the substeps), like every other scheme.
    long reported = 0;
    for (int step = 0; step < 5; ++step) reported += system.step(*integrator, 0.005).forceEvaluations;
    EXPECT_EQ(reported, static_cast<long>(counter.seen.size())) << info.name;
    EXPECT_GT(reported, 0) << info.name;
  }
}

TEST(StepStats, SumsCountsKeepsTheLargestResidualAndTheFirstFailure) {
  StepStats a;
  a.solves = 2, a.cgIterations = 7, a.maxResidual = 1e-9, a.factorizations = 1, a.forceEvaluations = 2;
  StepStats b;
  b.solves = 3, b.cgIterations = 5, b.maxResidual = 1e-7, b.rejectedSteps = 2, b.forceEvaluations = 4;
  b.failure = StepFailure::WorkCapReached;
  StepStats c;
  c.failure = StepFailure::SolveFailed;
  a += b;
  a += c;
  EXPECT_EQ(a.solves, 5);
  EXPECT_EQ(a.cgIterations, 12);
  EXPECT_EQ(a.maxResidual, 1e-7);
  EXPECT_EQ(a.factorizations, 1);
  EXPECT_EQ(a.forceEvaluations, 6);
  EXPECT_EQ(a.internalSteps, 3);
  EXPECT_EQ(a.rejectedSteps, 2);
  EXPECT_EQ(a.failure, StepFailure::WorkCapReached);
}

// A force that turns non-finite makes the constraint solve's right-hand side
// NaN: the solve fails, λ is not handed on as NaN, and the step says so.
class PoisonForce : public Force {
 public:
  const char* type() const override { return "poison"; }
  void apply(const Phase&, Eigen::VectorXd& f) const override {
    if (active) f[2] += std::numeric_limits<double>::quiet_NaN();
  }
  bool active = false;
};

TEST(StepStats, AFailedConstraintSolveIsReportedAndIsADivergence) {
  ParticleSystem system = makeChain();
  auto& poison = static_cast<PoisonForce&>(system.addForce(std::make_unique<PoisonForce>()));
  auto rk4 = makeIntegrator("rk4");
  const double e0 = system.totalEnergy();
  EXPECT_EQ(system.step(*rk4, 0.01).failure, StepFailure::None);
  poison.active = true;
  const StepStats stats = system.step(*rk4, 0.01);
  EXPECT_EQ(stats.failure, StepFailure::SolveFailed);
  EXPECT_TRUE(system.lastSolve().failed);
  EXPECT_TRUE(system.solver().lambda().allFinite());
  const Divergence d = checkDivergence(system, DivergenceLimits{}, e0, stats);
  EXPECT_TRUE(d);  // the NaN force reached the state too, so it is non-finite first
  EXPECT_EQ(d.reason, DivergenceReason::NonFinite);
}

// --- divergence -------------------------------------------------------------------

TEST(Divergence, ACalmStateIsNotDiverged) {
  ParticleSystem system = makeChain();
  DivergenceLimits limits;
  limits.energyScale = 1.0;
  const Divergence d = checkDivergence(system, limits, system.totalEnergy(), StepStats{});
  EXPECT_FALSE(d);
  EXPECT_EQ(d.reason, DivergenceReason::None);
}

TEST(Divergence, EachReasonTriggersOnItsOwn) {
  const StepStats fine;
  {
    ParticleSystem system = makeChain();
    system.setVelocity(1, Vector2d(system.velocity(1).x(), 1e200));  // |v|² overflows although v is finite
    const Divergence d = checkDivergence(system, DivergenceLimits{}, 0.0, fine);
    EXPECT_EQ(d.reason, DivergenceReason::NonFinite);
    EXPECT_STREQ(divergenceReasonName(d.reason), "non-finite");
  }
  {
    ParticleSystem system = makeChain();
    StepStats failed;
    failed.failure = StepFailure::WorkCapReached;
    const Divergence d = checkDivergence(system, DivergenceLimits{}, 0.0, failed);
    EXPECT_EQ(d.reason, DivergenceReason::StepFailed);
    EXPECT_NE(d.message().find("work-cap"), std::string::npos) << d.message();
  }
  {
    ParticleSystem system = makeChain();
    system.setPosition(4, system.position(4) - Vector2d(0.02, 0.0));  // the last rod 20% short
    DivergenceLimits limits;
    const Divergence relative = checkDivergence(system, limits, 0.0, fine);
    EXPECT_EQ(relative.reason, DivergenceReason::ConstraintViolation);
    // The message names the measure: relative to the rod's length here.
    EXPECT_TRUE(relative.relative);
    EXPECT_NE(relative.message().find("relative constraint error max |C|/r reached 0.2"), std::string::npos)
        << relative.message();
    limits.maxRelativeConstraintError = 0.5;
    EXPECT_FALSE(checkDivergence(system, limits, 0.0, fine));
    limits.maxConstraintError = 1e-3;  // world units
    const Divergence d = checkDivergence(system, limits, 0.0, fine);
    EXPECT_EQ(d.reason, DivergenceReason::ConstraintViolation);
    EXPECT_GT(d.value, d.limit);
    EXPECT_FALSE(d.relative);
    EXPECT_NE(d.message().find("max |C| reached 0.02 (world units)"), std::string::npos) << d.message();
  }
  {
    ParticleSystem system = makeChain();
    const double e0 = system.totalEnergy();
    system.setVelocity(4, Vector2d(system.velocity(4).x(), 2.0));  // kinetic energy 2
    DivergenceLimits limits;
    EXPECT_FALSE(checkDivergence(system, limits, e0, fine));  // energy test off without a scale
    limits.energyScale = 10.0;
    limits.energyRiseFraction = 0.3;  // allows 3
    EXPECT_FALSE(checkDivergence(system, limits, e0, fine));
    limits.energyRiseFraction = 0.1;  // allows 1
    const Divergence d = checkDivergence(system, limits, e0, fine);
    EXPECT_EQ(d.reason, DivergenceReason::EnergyGrowth);
    EXPECT_NEAR(d.value, 2.0, 1e-12);
    EXPECT_NEAR(d.limit, 1.0, 1e-12);
  }
  {
    ParticleSystem system = makeChain();
    DivergenceLimits limits;
    limits.maxCoordinate = 0.3;
    EXPECT_EQ(checkDivergence(system, limits, 0.0, fine).reason, DivergenceReason::OutOfBounds);
  }
}

// E_ref = |E(0)| + K(0) + Σ|V_f(0)| + L Σ|F_i(0)|: for 2 kg at rest at the
// origin under g = 9.81 (E, K and V all zero) it is the weight times L; a
// pinned particle adds no force, a moving one its kinetic energy twice
// (in E and in K).
TEST(Divergence, BlowUpEnergyScaleIsTheEnergiesAndTheWorkOfTheForcesAcrossTheScene) {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 0.0), 2.0);
  system.addParticle(Vector2d(0.0, 0.0), 5.0);
  system.setPinned(1, true);
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  EXPECT_NEAR(blowUpEnergyScale(system, 3.0), 2.0 * 9.81 * 3.0, 1e-12);
  system.setVelocity(0, Vector2d(1.0, system.velocity(0).y()));  // K = 1 J
  EXPECT_NEAR(blowUpEnergyScale(system, 3.0), 2.0 + 2.0 * 9.81 * 3.0, 1e-12);
  EXPECT_GT(blowUpEnergyScale(system, 0.0), 0.0);
}

TEST(Divergence, LimitsMustBePositiveAndNotNaN) {
  DivergenceLimits limits;
  limits.validate();
  limits.energyRiseFraction = std::nan("");
  test_support::expectRejected([&] { limits.validate(); }, "energyRiseFraction");
  limits = {};
  limits.maxRelativeConstraintError = 0.0;
  test_support::expectRejected([&] { limits.validate(); }, "maxRelativeConstraintError");
}

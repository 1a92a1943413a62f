// RATTLE against closed forms and its own invariants: the energy error of a
// constrained system stays bounded over thousands of periods, the constraints
// hold to the projection tolerance at every step, and the global error is of
// order 2 on the large-angle pendulum (whose period is a closed form).
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "particles/constants.h"
#include "integrators/rattle.h"
#include "particles/particle_system.h"
#include "scenes/pendulum.h"
#include "scenes/test_chain.h"
#include "test_support.h"

using namespace particles;

namespace {

double worstRelativeViolation(const ParticleSystem& system) { return system.maxRelativeConstraintError(); }

// Largest |E(t) − E(0)| over the steps of [from, to) of a run of `steps`
// steps of dt, sampled every step; also the largest relative violation seen.
struct EnergyWindows {
  std::vector<double> worstDeviation;  // one per window
  double worstViolation = 0.0;
  bool failed = false;
};

EnergyWindows runWindows(ParticleSystem& system, double dt, long steps, int windows) {
  RattleIntegrator rattle;
  EnergyWindows out;
  out.worstDeviation.assign(windows, 0.0);
  const double e0 = system.totalEnergy();
  for (long k = 0; k < steps; ++k) {
    const StepStats stats = system.step(rattle, dt);
    out.failed |= stats.failure != StepFailure::None;
    const int window = static_cast<int>(k * windows / steps);
    out.worstDeviation[window] = std::max(out.worstDeviation[window], std::abs(system.totalEnergy() - e0));
    out.worstViolation = std::max(out.worstViolation, worstRelativeViolation(system));
  }
  return out;
}

}  // namespace

// A bead on a 1 cm wire released at 60°: period 0.2166 s, so 10⁴ periods are
// 2166 s, at 40 steps a period (4·10⁵ steps). A drifting scheme's energy error
// grows with time; RATTLE's stays within the band of the first tenth of the run.
TEST(Rattle, PendulumEnergyErrorDoesNotGrowOverTenThousandPeriods) {
  scenes::PendulumParams p;
  p.length = 0.01;
  const double period = scenes::pendulumPeriod(p);
  scenes::Scene scene = scenes::buildPendulum(p);
  ParticleSystem& system = *scene.system;
  const double releasable = p.mass * p.gravity * p.length * (1.0 - std::cos(p.angle * kPi / 180.0));
  const double dt = period / 40.0;
  const long steps = 400000;  // 10⁴ periods
  const EnergyWindows w = runWindows(system, dt, steps, 10);
  EXPECT_FALSE(w.failed);
  const double first = w.worstDeviation.front(), last = w.worstDeviation.back();
  std::printf("pendulum: |dE| first tenth %.3e, last tenth %.3e of E_s %.3e; max |C|/L %.2e\n", first, last,
              releasable, w.worstViolation);
  EXPECT_LT(first, 0.01 * releasable);  // O(h²) band at 40 steps a period
  EXPECT_LE(last, 1.1 * first) << "the energy error grew over the run";
  EXPECT_LE(w.worstViolation, 1e-10);
}

// The seed's 6-particle test chain (5 rods, first particle pinned), released
// horizontally: chaotic, yet its energy error stays in a band that does not
// widen with time, and every rod holds its length at every step.
TEST(Rattle, ChainEnergyErrorStaysBoundedAndRodsHold) {
  scenes::TestChainParams p = scenes::TestChainParams::seed();
  p.cl = 6;
  scenes::Scene scene = scenes::buildTestChain(p);
  ParticleSystem& system = *scene.system;
  const double releasable = p.gravity * p.mass * p.length * p.cl * (p.cl - 1) / 2.0;
  const double dt = scene.dt;
  const long steps = 200000;
  const EnergyWindows w = runWindows(system, dt, steps, 10);
  EXPECT_FALSE(w.failed);
  const double first = w.worstDeviation.front();
  const double later = *std::max_element(w.worstDeviation.begin() + 1, w.worstDeviation.end());
  std::printf("6-chain, dt %g, %ld steps: |dE| first tenth %.3e, worst later tenth %.3e of E_s %.3e; max |C|/L %.2e\n",
              dt, steps, first, later, releasable, w.worstViolation);
  EXPECT_LT(later, 0.05 * releasable);
  EXPECT_LE(later, 3.0 * first) << "the energy error band widened";
  EXPECT_LE(w.worstViolation, 1e-10);
}

// A quarter period after its release from rest the bead passes the bottom
// of the wire (a closed form through the elliptic period): the distance from
// the bottom is the global error there, where the speed is largest, and it
// falls as dt². (At a whole period the bead is at a turning point, where a
// symmetric scheme's phase error costs only O(h⁴) in position.)
TEST(Rattle, GlobalErrorOnTheLargeAnglePendulumIsSecondOrder) {
  scenes::PendulumParams p;
  const double period = scenes::pendulumPeriod(p);
  std::vector<double> dts, errors;
  for (int steps : {50, 100, 200, 400}) {
    scenes::Scene scene = scenes::buildPendulum(p);
    ParticleSystem& system = *scene.system;
    const Eigen::Vector2d centre = system.position(0) + Eigen::Vector2d(-std::sin(p.angle * kPi / 180.0),
                                                                            std::cos(p.angle * kPi / 180.0)) *
                                                               p.length;
    const Eigen::Vector2d bottom = centre - Eigen::Vector2d(0.0, p.length);
    RattleIntegrator rattle;
    const double dt = 0.25 * period / steps;
    for (int k = 0; k < steps; ++k) system.step(rattle, dt);
    dts.push_back(dt);
    errors.push_back((system.position(0) - bottom).norm());
  }
  for (std::size_t k = 1; k < dts.size(); ++k) {
    const double slope = test_support::logLogSlope({dts[k - 1], dts[k]}, {errors[k - 1], errors[k]});
    EXPECT_NEAR(slope, 2.0, 0.15) << "between steps " << k - 1 << " and " << k;
  }
}

// A moving start: the bead launched along the wire from the bottom keeps its
// radius and its energy (no gravity: the speed is constant, a closed form).
TEST(Rattle, BeadLaunchedAlongTheWireKeepsItsSpeedWithoutGravity) {
  scenes::PendulumParams p;
  p.gravity = 0.0;
  p.angle = 0.0;
  scenes::Scene scene = scenes::buildPendulum(p);
  ParticleSystem& system = *scene.system;
  system.setVelocities(Eigen::VectorXd::Zero(2 * system.size()));
  system.setVelocity(0, Eigen::Vector2d(2.0, 0.0));  // tangent at the bottom
  RattleIntegrator rattle;
  for (int k = 0; k < 2000; ++k) system.step(rattle, 0.005);
  EXPECT_NEAR(system.velocity(0).norm(), 2.0, 1e-9);
  EXPECT_LE(system.maxRelativeConstraintError(), 1e-10);
}

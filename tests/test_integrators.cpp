// Integrators against problems with known solutions: the order of the global
// error on a harmonic oscillator, energy behaviour over many periods, a bead
// on a circular wire, and free fall.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "particles/constants.h"
#include "particles/constraints/circular_wire.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/particle_system.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

// Mass m on an undamped spring of stiffness k and rest length r to a pinned
// particle at the origin, released at rest from x = r + A on the x axis:
//   x(t) = r + A cos ωt,  v(t) = −A ω sin ωt,  ω = √(k/m).
struct Oscillator {
  double mass = 1.0;
  double stiffness = 4.0 * particles::kPi * particles::kPi;  // period 1 s
  double rest = 1.0;
  double amplitude = 0.1;
  double omega() const { return std::sqrt(stiffness / mass); }

  ParticleSystem build() const {
    ParticleSystem system;
    system.addParticle(Vector2d::Zero(), 1.0);
    system.addParticle(Vector2d(rest + amplitude, 0.0), mass);
    system.setPinned(0, true);
    system.addForce(std::make_unique<SpringForce>(0, 1, rest, stiffness, 0.0));
    return system;
  }

  // Phase-space distance from the exact solution at time t, in length units.
  double error(const ParticleSystem& system, double t) const {
    const double x = rest + amplitude * std::cos(omega() * t);
    const double v = -amplitude * omega() * std::sin(omega() * t);
    const Vector2d dx = system.position(1) - Vector2d(x, 0.0);
    const Vector2d dv = system.velocity(1) - Vector2d(v, 0.0);
    return std::sqrt(dx.squaredNorm() + dv.squaredNorm() / (omega() * omega()));
  }
};

// Least-squares slope of log(error) against log(dt).
double fittedOrder(const std::vector<double>& dt, const std::vector<double>& error) {
  const int n = static_cast<int>(dt.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int k = 0; k < n; ++k) {
    const double x = std::log(dt[k]), y = std::log(error[k]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// Each scheme's expected global order, and step counts over T that sit in its
// asymptotic range while keeping the error far above rounding.
struct OrderCase {
  const char* name;
  int order;
  std::vector<int> steps;
};
const OrderCase kOrderCases[] = {
    {"euler", 1, {4000, 8000, 16000, 32000}},
    {"symplectic-euler", 1, {4000, 8000, 16000, 32000}},
    {"midpoint", 2, {200, 400, 800, 1600}},
    {"rk4", 4, {20, 40, 80, 160}},
    {"rattle", 2, {200, 400, 800, 1600}},  // velocity Verlet without constraints
    {"xpbd", 1, {200, 400, 800, 1600}},  // 20 substeps each: h as euler's
};

}  // namespace

TEST(Integrators, GlobalErrorOnHarmonicOscillatorHasTheExpectedOrder) {
  const Oscillator oscillator;
  const double T = 1.3;  // not a whole number of periods
  for (const OrderCase& c : kOrderCases) {
    SCOPED_TRACE(c.name);
    std::vector<double> dts, errors;
    for (int steps : c.steps) {
      ParticleSystem system = oscillator.build();
      auto integrator = makeIntegrator(c.name);
      const double dt = T / steps;
      for (int k = 0; k < steps; ++k) system.step(*integrator, dt);
      EXPECT_NEAR(system.time(), T, 1e-9);
      dts.push_back(dt);
      errors.push_back(oscillator.error(system, T));
    }
    const double order = fittedOrder(dts, errors);
    EXPECT_NEAR(order, c.order, 0.3) << "errors from " << errors.front() << " to " << errors.back();
  }
}

TEST(Integrators, TableGivesEachSchemeItsTestedOrder) {
  for (const OrderCase& c : kOrderCases) {
    bool found = false;
    for (const IntegratorInfo& info : integratorTable())
      if (c.name == std::string(info.name)) {
        found = true;
        EXPECT_EQ(info.order, c.order) << c.name;
      }
    EXPECT_TRUE(found) << c.name << " is missing from integratorTable()";
  }
}

// Over 20 periods at ωh ≈ 0.03 explicit Euler multiplies the energy by
// (1 + ω²h²) every step (≈ e^3.9 in all); symplectic Euler's energy error
// oscillates at O(ωh) without drift.
TEST(Integrators, SymplecticEulerEnergyStaysBoundedWhileExplicitEulerGrows) {
  const Oscillator oscillator;
  const double dt = 0.005;
  const int stepsPerPeriod = 200, periods = 20;

  auto relativeEnergyDeviation = [&](const char* name) {
    ParticleSystem system = oscillator.build();
    auto integrator = makeIntegrator(name);
    const double e0 = system.totalEnergy();
    std::vector<double> worstPerPeriod(periods, 0.0), endOfPeriod(periods);
    for (int p = 0; p < periods; ++p) {
      for (int k = 0; k < stepsPerPeriod; ++k) {
        system.step(*integrator, dt);
        worstPerPeriod[p] = std::max(worstPerPeriod[p], std::abs(system.totalEnergy() - e0) / e0);
      }
      endOfPeriod[p] = system.totalEnergy() / e0;
    }
    return std::make_pair(worstPerPeriod, endOfPeriod);
  };

  const auto [symplecticWorst, symplecticEnd] = relativeEnergyDeviation("symplectic-euler");
  const double firstFew = *std::max_element(symplecticWorst.begin(), symplecticWorst.begin() + 5);
  const double lastFew = *std::max_element(symplecticWorst.end() - 5, symplecticWorst.end());
  EXPECT_LT(firstFew, 0.05);
  EXPECT_LT(lastFew, 1.05 * firstFew) << "symplectic Euler's energy error drifts";

  const auto [eulerWorst, eulerEnd] = relativeEnergyDeviation("euler");
  for (int p = 1; p < periods; ++p) EXPECT_GT(eulerEnd[p], eulerEnd[p - 1]) << "period " << p;
  EXPECT_GT(eulerEnd.back(), 10.0);
}

// RK4 at dt = 0.01 for 10 simulated seconds with the default feedback gains.
TEST(Rk4, BeadOnCircularWireKeepsItsRadius) {
  const double radius = 0.5;
  const Vector2d centre(0.2, 0.1);
  ParticleSystem system;
  system.addParticle(centre + Vector2d(radius, 0.0), 1.0);
  system.addConstraint(std::make_unique<CircularWireConstraint>(0, centre, radius));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  auto rk4 = makeIntegrator("rk4");
  double worst = 0.0, lowest = 0.0;
  for (int step = 0; step < 1000; ++step) {
    system.step(*rk4, 0.01);
    const Vector2d d = system.position(0) - centre;
    worst = std::max(worst, std::abs(d.norm() - radius));
    lowest = std::min(lowest, d.y());
  }
  EXPECT_NEAR(system.time(), 10.0, 1e-9);
  EXPECT_LT(worst, 1e-3 * radius);
  EXPECT_LT(lowest, -0.99 * radius) << "the bead should swing through the bottom of the wire";
}

// Constant acceleration: midpoint and RK4 are exact up to rounding.
TEST(Integrators, FreeParticleUnderGravityFollowsTheParabola) {
  const Vector2d x0(0.3, 2.0), v0(1.5, 4.0), g(0.0, -9.81);
  for (const char* name : {"midpoint", "rk4"}) {
    SCOPED_TRACE(name);
    ParticleSystem system;
    system.addParticle(x0, 0.7, v0);
    system.addForce(std::make_unique<GravityForce>(g));
    auto integrator = makeIntegrator(name);
    for (int step = 1; step <= 200; ++step) {
      system.step(*integrator, 0.01);
      const double t = 0.01 * step;
      EXPECT_LT((system.position(0) - (x0 + v0 * t + 0.5 * g * t * t)).norm(), 1e-11) << "t " << t;
      EXPECT_LT((system.velocity(0) - (v0 + g * t)).norm(), 1e-11) << "t " << t;
    }
  }
}

TEST(Integrators, EveryTableEntryIsMadeByItsName) {
  for (const IntegratorInfo& info : integratorTable()) {
    auto integrator = makeIntegrator(info.name);
    ASSERT_NE(integrator, nullptr);
    EXPECT_STREQ(integrator->name(), info.name);
  }
}

TEST(Integrators, FixedStepSchemesReportDtAsTheirInternalStep) {
  for (const OrderCase& c : kOrderCases) {
    auto integrator = makeIntegrator(c.name);
    ParticleSystem system;
    system.addParticle(Vector2d::Zero(), 1.0);
    system.step(*integrator, 0.02);
    // Substepping schemes report their substep.
    const bool substepping = requireIntegrator(c.name).usesSubsteps;
    const double expected = substepping ? 0.02 / IntegratorSettings{}.xpbd.substeps : 0.02;
    EXPECT_DOUBLE_EQ(integrator->lastInternalStep(), expected) << c.name;
  }
}

TEST(Integrators, LookupByNameFindsEveryTableEntryAndNothingElse) {
  std::string names;
  for (const IntegratorInfo& info : integratorTable()) {
    EXPECT_EQ(findIntegrator(info.name), &info) << info.name;
    EXPECT_EQ(&requireIntegrator(info.name), &info) << info.name;
    names += (names.empty() ? "" : ", ") + std::string(info.name);
  }
  EXPECT_EQ(integratorNames(), names);
  for (const char* unknown : {"leapfrog", "", "RK4", "rk4 ", "euler,rk4"}) {
    EXPECT_EQ(findIntegrator(unknown), nullptr) << unknown;
    test_support::expectRejected([&] { requireIntegrator(unknown); },
                                 "unknown integrator '" + std::string(unknown) + "' (valid: " + names + ")");
  }
}

TEST(Integrators, UnknownNameThrowsListingTheValidNames) {
  for (const IntegratorInfo& info : integratorTable())
    test_support::expectRejected([] { makeIntegrator("leapfrog"); }, info.name);
  test_support::expectRejected([] { makeIntegrator("leapfrog"); }, "leapfrog");
}

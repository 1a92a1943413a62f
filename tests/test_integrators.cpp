// Integrators against problems with known solutions: the order of every
// registered scheme's global error on a harmonic oscillator, energy behaviour
// over many periods, a bead on a circular wire, and free fall.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "particles/constraints/circular_wire.h"
#include "particles/forces/gravity.h"
#include "particles/particle_system.h"
#include "oscillator_fixture.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

// Each scheme's expected global order on the oscillator, and step counts over
// T that sit in its asymptotic range while keeping the error far above
// rounding. Checked both ways against the engine's integratorTable(): every
// registered scheme has a case here with the table's order, and every case is
// a registered scheme, so a new integrator cannot escape the measurement.
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
    {"verlet", 2, {200, 400, 800, 1600}},  // velocity Verlet: second order in x and v
    {"rattle", 2, {200, 400, 800, 1600}},  // velocity Verlet without constraints
    {"implicit-euler", 1, {4000, 8000, 16000, 32000}},
    {"dopri5", 5, {20, 40, 80, 160}},      // on fixed steps (kFixedSteps)
    {"xpbd", 1, {200, 400, 800, 1600}},    // 20 substeps each: h as euler's
};

// dopri5 on the steps it is given, not the internal steps its tolerance would
// choose; every other scheme ignores these settings.
const IntegratorSettings kFixedSteps = [] {
  IntegratorSettings settings;
  settings.dopri5.adaptive = false;
  return settings;
}();

const OrderCase* findOrderCase(const std::string& name) {
  for (const OrderCase& c : kOrderCases)
    if (name == c.name) return &c;
  return nullptr;
}

}  // namespace

TEST(Integrators, GlobalErrorOnHarmonicOscillatorHasTheExpectedOrder) {
  const test_support::Oscillator oscillator;
  const double T = 1.3;  // not a whole number of periods
  for (const IntegratorInfo& info : integratorTable()) {
    SCOPED_TRACE(info.name);
    const OrderCase* c = findOrderCase(info.name);
    if (!c) continue;  // TableAndOrderCasesNameTheSameSchemes fails for it
    const test_support::OrderFit fit = oscillator.measureOrder(c->name, T, c->steps, kFixedSteps);
    RecordProperty(std::string("fitted_order_") + c->name, std::to_string(fit.order));
    EXPECT_NEAR(fit.order, c->order, 0.3) << "errors from " << fit.errors.front() << " to " << fit.errors.back();
  }
}

TEST(Integrators, TableAndOrderCasesNameTheSameSchemes) {
  for (const IntegratorInfo& info : integratorTable()) {
    const OrderCase* c = findOrderCase(info.name);
    if (!c) {
      ADD_FAILURE() << info.name << " is registered in integratorTable() but has no case in kOrderCases";
      continue;
    }
    EXPECT_EQ(info.order, c->order) << info.name;
  }
  for (const OrderCase& c : kOrderCases)
    EXPECT_NE(findIntegrator(c.name), nullptr) << c.name << " is in kOrderCases but not in integratorTable()";
}

// Over 20 periods at ωh ≈ 0.03 explicit Euler multiplies the energy by
// (1 + ω²h²) every step (≈ e^3.9 in all); symplectic Euler's energy error
// oscillates at O(ωh) without drift.
TEST(Integrators, SymplecticEulerEnergyStaysBoundedWhileExplicitEulerGrows) {
  const test_support::Oscillator oscillator;
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
  for (const IntegratorInfo& info : integratorTable()) {
    if (info.usesTolerance) continue;  // adaptive: its own step
    auto integrator = makeIntegrator(info.name);
    ParticleSystem system;
    system.addParticle(Vector2d::Zero(), 1.0);
    system.step(*integrator, 0.02);
    // Substepping schemes report their substep.
    const double expected = info.usesSubsteps ? 0.02 / IntegratorSettings{}.xpbd.substeps : 0.02;
    EXPECT_DOUBLE_EQ(integrator->lastInternalStep(), expected) << info.name;
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

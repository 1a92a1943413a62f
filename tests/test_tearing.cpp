// Tearing: springs break where their strain passes the scene's limit and
// nowhere else, once per step at its end, and stay broken through every
// stage of every integrator; what hangs on a broken link goes with it.
#include <algorithm>
#include <cmath>
#include <memory>
#include <map>

#include <gtest/gtest.h>

#include "particles/constants.h"
#include "particles/forces/angular_spring.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/forces/wind.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "particles/tearing.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

std::vector<const SpringForce*> springsOf(const ParticleSystem& system) {
  std::vector<const SpringForce*> springs;
  for (const auto& force : system.forceObjects())
    if (const auto* spring = dynamic_cast<const SpringForce*>(force.get())) springs.push_back(spring);
  return springs;
}

// A w × h cloth of 4-way springs (rest 0.1, k 100, k_d 0.2, 10 g particles),
// its top row pinned; no gravity.
ParticleSystem pinnedCloth(int w, int h) {
  ParticleSystem system;
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col) system.addParticle(Vector2d(0.1 * col, -0.1 * row), 0.01);
  const auto id = [&](int row, int col) { return row * w + col; };
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col) {
      if (col + 1 < w) system.addForce(std::make_unique<SpringForce>(id(row, col), id(row, col + 1), 0.1, 100.0, 0.2));
      if (row + 1 < h) system.addForce(std::make_unique<SpringForce>(id(row, col), id(row + 1, col), 0.1, 100.0, 0.2));
    }
  for (int col = 0; col < w; ++col) system.setPinned(id(0, col), true);
  return system;
}

}  // namespace

// A 6 × 10 cloth hangs from its pinned top row; its bottom row is pinned too,
// the left half held still and the right half moved down at 1 m/s, which
// shears the cloth between columns 2 and 3 and stretches the right half.
// With a tear strain of 0.3: at every step's end every intact spring is
// within the limit and each spring that tore was beyond it at the end of the
// step it tore in; the first to tear is the bottom spring across the shear,
// where the strain is largest; more follow as the pull goes on; no spring of
// the left half, which does not move, tears.
TEST(Tearing, AClothTearsWhereItsStrainPassesTheLimitAndNowhereElse) {
  const int kRows = 10, kSteps = 800;  // 0.4 s: the right half moves 0.4 m
  for (const IntegratorInfo& info : integratorTable()) {
    SCOPED_TRACE(info.name);
    ParticleSystem system = pinnedCloth(6, kRows);
    system.tearing().strain = 0.3;
    const int bottom = 6 * (kRows - 1);
    for (int col = 0; col < 6; ++col) {
      system.setPinned(bottom + col, true);
      // Pinned particles keep their velocity: every integrator moves them with it.
      if (col >= 3) system.setVelocity(bottom + col, Eigen::Vector2d(system.velocity(bottom + col).x(), -1.0));  // m/s
    }
    const auto integrator = makeIntegrator(info.name);
    const std::vector<const SpringForce*> springs = springsOf(system);
    std::map<const SpringForce*, int> tornAt;
    for (int step = 0; step < kSteps; ++step) {
      ASSERT_EQ(system.step(*integrator, 0.0005).failure, StepFailure::None);
      for (const SpringForce* spring : springs) {
        const double strain = spring->strain(system.positions());
        if (spring->enabled()) {
          EXPECT_LE(strain, 0.3) << "an intact spring beyond the limit at step " << step;
        } else if (!tornAt.count(spring)) {
          tornAt[spring] = step;
          EXPECT_GT(strain, 0.3) << "spring " << spring->first() << "-" << spring->second() << " tore within the limit";
        }
      }
    }
    ASSERT_GE(tornAt.size(), 3u) << "the tear did not run on from the first";
    const auto across = [](const SpringForce* s) {  // a spring from column 2 to column 3
      return std::min(s->first() % 6, s->second() % 6) == 2 && std::max(s->first() % 6, s->second() % 6) == 3;
    };
    const SpringForce* first = tornAt.begin()->first;
    for (const auto& [spring, step] : tornAt)
      if (step < tornAt.at(first)) first = spring;
    EXPECT_TRUE(across(first) && first->first() / 6 == kRows - 1) << "first torn: " << first->first() << "-" << first->second();
    for (const auto& [spring, step] : tornAt)
      EXPECT_GE(std::max(spring->first() % 6, spring->second() % 6), 3)
          << "spring " << spring->first() << "-" << spring->second() << " of the still left half tore";
    EXPECT_EQ(system.brokenLinks().size(), tornAt.size());
  }
}

// Two free particles on a spring flying apart: it tears at the end of the
// step that takes its strain past the limit, and from then on they fly at
// constant velocity, to rounding, under every integrator: no stage of
// any step (RK4's four evaluations, xpbd's substeps and compliant springs,
// implicit Euler's Newton passes) sees the torn spring.
TEST(Tearing, ATornSpringStaysTornThroughEveryStageOfEveryIntegrator) {
  for (const IntegratorInfo& info : integratorTable()) {
    SCOPED_TRACE(info.name);
    ParticleSystem system;
    system.addParticle(Vector2d(0.0, 0.0), 1.0, Vector2d(-1.0, 0.0));
    system.addParticle(Vector2d(1.0, 0.0), 1.0, Vector2d(1.0, 0.0));
    const Force& spring = system.addForce(std::make_unique<SpringForce>(0, 1, 1.0, 10.0, 0.5));
    system.tearing().strain = 0.05;
    const auto integrator = makeIntegrator(info.name);
    // The same run without tearing, to compare the step the spring tears in.
    ParticleSystem intact;
    intact.addParticle(Vector2d(0.0, 0.0), 1.0, Vector2d(-1.0, 0.0));
    intact.addParticle(Vector2d(1.0, 0.0), 1.0, Vector2d(1.0, 0.0));
    intact.addForce(std::make_unique<SpringForce>(0, 1, 1.0, 10.0, 0.5));
    const auto intactIntegrator = makeIntegrator(info.name);
    int tornAt = -1;
    for (int step = 0; step < 100 && tornAt < 0; ++step) {
      system.step(*integrator, 0.01);
      intact.step(*intactIntegrator, 0.01);
      // Tearing comes after the step: the step's end state is the intact run's.
      EXPECT_EQ(system.positions(), intact.positions());
      if (system.tornLastStep() > 0) tornAt = step;
    }
    ASSERT_GE(tornAt, 0) << "the spring never tore";
    EXPECT_FALSE(static_cast<const SpringForce&>(spring).enabled());
    EXPECT_GT(static_cast<const SpringForce&>(spring).strain(system.positions()), 0.05);
    const Eigen::VectorXd v = system.velocities();
    for (int step = 0; step < 50; ++step) {
      const Eigen::VectorXd x = system.positions();
      system.step(*integrator, 0.01);
      EXPECT_LT((system.velocities() - v).norm(), 1e-12) << "step " << step << " after the tear";
      EXPECT_LT((system.positions() - x - 0.01 * v).norm(), 1e-12) << "step " << step << " after the tear";
      EXPECT_EQ(system.tornLastStep(), 0);
    }
    EXPECT_EQ(system.potentialEnergy(), 0.0);
  }
}

// A cloth blown down by gusts until its springs tear: two runs tear the
// same links at the same steps and end in the same state, bit for bit.
TEST(Tearing, TwoRunsTearTheSameSpringsAtTheSameSteps) {
  WindSettings gusts;
  gusts.speed = 8.0;
  gusts.direction = -0.5 * particles::kPi;  // down, across the hem
  gusts.drag = 0.05;
  gusts.gust = 0.7;
  gusts.gustPeriod = 0.3;
  const auto run = [&](std::vector<int>& tears) {
    ParticleSystem system = pinnedCloth(5, 5);
    system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
    system.addForce(std::make_unique<WindForce>(std::vector<std::array<int, 2>>{{20, 21}, {21, 22}, {22, 23}, {23, 24}},
                                                gusts));
    system.tearing().strain = 0.12;
    const auto rk4 = makeIntegrator("rk4");
    for (int step = 0; step < 1500; ++step) {
      system.step(*rk4, 0.001);
      tears.push_back(system.tornLastStep());
    }
    return std::make_pair(system.brokenLinks(), system.positions());
  };
  std::vector<int> first, second;
  const auto [linksA, positionsA] = run(first);
  const auto [linksB, positionsB] = run(second);
  EXPECT_GT(linksA.size(), 1u);
  EXPECT_EQ(first, second);
  EXPECT_EQ(linksA, linksB);
  EXPECT_EQ(positionsA, positionsB);
}

// What hangs on a broken link: the spring on it, the angle springs with it
// as an arm, the wind's edge on it and the collision edge on it.
TEST(Tearing, BreakingALinkTakesEverythingThatHangsOnIt) {
  ParticleSystem system;
  for (int i = 0; i < 4; ++i) system.addParticle(Vector2d(0.1 * i, 0.0), 1.0);
  const auto& s01 = static_cast<const SpringForce&>(system.addForce(std::make_unique<SpringForce>(0, 1, 0.1, 10.0, 0.0)));
  const auto& s12 = static_cast<const SpringForce&>(system.addForce(std::make_unique<SpringForce>(1, 2, 0.1, 10.0, 0.0)));
  const auto& a012 = static_cast<const AngularSpringForce&>(
      system.addForce(std::make_unique<AngularSpringForce>(0, 1, 2, 3.0, 1.0, 0.0)));
  const auto& a123 = static_cast<const AngularSpringForce&>(
      system.addForce(std::make_unique<AngularSpringForce>(1, 2, 3, 3.0, 1.0, 0.0)));
  WindSettings w;
  w.speed = 1.0;
  w.drag = 0.1;
  const auto& wind = static_cast<const WindForce&>(
      system.addForce(std::make_unique<WindForce>(std::vector<std::array<int, 2>>{{0, 1}, {1, 2}, {2, 3}}, w)));
  system.addCollisionEdge(1, 0);
  system.addCollisionEdge(2, 3);
  const auto stamp = system.structureStamp();

  EXPECT_EQ(system.breakLinks({{1, 0}}), 3);  // the spring, one angle spring, the wind
  EXPECT_NE(system.structureStamp(), stamp);
  EXPECT_FALSE(s01.enabled());
  EXPECT_TRUE(s12.enabled());
  EXPECT_FALSE(a012.enabled());
  EXPECT_TRUE(a123.enabled());
  EXPECT_EQ(wind.edges(), (std::vector<std::array<int, 2>>{{1, 2}, {2, 3}}));
  ASSERT_EQ(system.collisionEdges().size(), 1u);
  EXPECT_EQ(system.collisionEdges()[0].a, 2);
  EXPECT_EQ(system.brokenLinks(), (std::vector<std::array<int, 2>>{{0, 1}}));
  // Nothing of the broken angle spring is left.
  Triplets dfdx, dfdv;
  a012.addJacobians(system.phase(), dfdx, dfdv);
  EXPECT_TRUE(dfdx.empty());
  EXPECT_EQ(a012.potential(system.phase()), 0.0);
  EXPECT_LT(test_support::forceAt(a012, system.phase()).norm(), 1e-300);
}

TEST(Tearing, ANegativeStrainIsRefusedBeforeTheStepMovesAnything) {
  ParticleSystem system = pinnedCloth(2, 2);
  system.tearing().strain = -0.1;
  const auto rk4 = makeIntegrator("rk4");
  const Eigen::VectorXd x = system.positions();
  test_support::expectRejected([&] { system.step(*rk4, 0.01); }, "tear strain");
  EXPECT_EQ(system.positions(), x);
  EXPECT_EQ(system.time(), 0.0);
}

// ParticleSystem: building and its parameter checks, pinning, the step and
// its clock, snapshots, and the energy and constraint diagnostics.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "particles/constraints/circular_wire.h"
#include "particles/constraints/line.h"
#include "particles/constraints/rod.h"
#include "particles/forces/angular_spring.h"
#include "particles/forces/gravity.h"
#include "particles/forces/mouse_spring.h"
#include "particles/forces/spring.h"
#include "particles/particle_system.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;
using test_support::expectRejected;

namespace {

// A pinned particle with a rod pendulum below it, a spring to a third
// particle, and gravity.
ParticleSystem makePendulum() {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 0.0), 1.0);
  system.addParticle(Vector2d(0.3, -0.4), 2.0, Vector2d(1.0, 0.75));
  system.addParticle(Vector2d(0.8, -0.4), 0.5);
  system.setPinned(0, true);
  system.addConstraint(std::make_unique<RodConstraint>(0, 1, 0.5));
  system.addForce(std::make_unique<SpringForce>(1, 2, 0.4, 10.0, 0.1));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  return system;
}

}  // namespace

// --- parameters ----------------------------------------------------------------

TEST(ParticleSystem, StepRejectsNonPositiveOrNanDtAndLeavesTheStateAlone) {
  ParticleSystem system = makePendulum();
  auto integrator = makeIntegrator("rk4");
  const Snapshot before = system.snapshot();
  for (double dt : {0.0, -0.01, std::nan(""), std::numeric_limits<double>::infinity()})
    expectRejected([&] { system.step(*integrator, dt); }, "dt");
  expectRejected([&] { system.step(*integrator, -0.25); }, "dt must be > 0, got -0.25");
  EXPECT_EQ(system.positions(), before.x);
  EXPECT_EQ(system.velocities(), before.v);
  EXPECT_EQ(system.time(), 0.0);
}

TEST(ParticleSystem, StepRejectsBadSettingsBeforeAnythingMoves) {
  ParticleSystem system = makePendulum();
  auto integrator = makeIntegrator("rk4");
  const Snapshot before = system.snapshot();
  system.solver().settings.tolerance = std::nan("");
  expectRejected([&] { system.step(*integrator, 0.01); }, "solver tolerance");
  system.solver().settings.tolerance = 1e-8;
  system.setCollidable(1, 0.05);
  system.setCollidable(2, 0.05);
  system.contactSettings().particleRestitution = 1.5;
  expectRejected([&] { system.step(*integrator, 0.01); }, "particle contact restitution");
  EXPECT_EQ(system.positions(), before.x);
  EXPECT_EQ(system.velocities(), before.v);
  EXPECT_EQ(system.time(), 0.0);
}

TEST(ParticleSystem, RejectedParticleIsNotAdded) {
  ParticleSystem system;
  for (double mass : {0.0, -1.0, std::nan("")})
    expectRejected([&] { system.addParticle(Vector2d::Zero(), mass); }, "particle mass");
  expectRejected([&] { system.addParticle(Vector2d::Zero(), -3.5); }, "got -3.5");
  expectRejected([&] { system.addParticle(Vector2d(std::nan(""), 0.0), 1.0); }, "particle position.x");
  expectRejected([&] { system.addParticle(Vector2d::Zero(), 1.0, Vector2d(0.0, std::nan(""))); },
                 "particle velocity.y");
  expectRejected([&] { system.addParticles({Vector2d::Zero(), Vector2d::Ones()}, {1.0, -2.0}); },
                 "particle mass");
  EXPECT_EQ(system.size(), 0);
  EXPECT_EQ(system.positions().size(), 0);
}

TEST(ParticleSystem, RadiusMustBePositive) {
  ParticleSystem system;
  system.addParticle(Vector2d::Zero(), 1.0);
  for (double radius : {0.0, -0.1, std::nan("")})
    expectRejected([&] { system.setCollidable(0, radius); }, "particle radius");
  EXPECT_FALSE(system.collidable(0));
  expectRejected([&] { system.setCollidable(3, 0.1); }, "particle 3");
  expectRejected([&] { system.setPinned(-1, true); }, "particle -1");
}

TEST(ParticleSystem, ForceOrConstraintNamingAMissingParticleIsRejected) {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 0.0), 1.0);
  system.addParticle(Vector2d(1.0, 0.0), 1.0);
  expectRejected([&] { system.addForce(std::make_unique<SpringForce>(0, 2, 1.0, 1.0, 0.0)); },
                 "spring names particle 2");
  expectRejected([&] { system.addForce(std::make_unique<AngularSpringForce>(0, 1, 7, 1.0, 1.0, 0.0)); },
                 "angular-spring names particle 7");
  expectRejected(
      [&] { system.addForce(std::make_unique<MouseSpringForce>(-1, Vector2d::Zero(), 1.0, 0.0)); },
      "mouse-spring names particle -1");
  expectRejected([&] { system.addConstraint(std::make_unique<RodConstraint>(4, 1, 1.0)); },
                 "rod names particle 4");
  expectRejected(
      [&] { system.addConstraint(std::make_unique<CircularWireConstraint>(2, Vector2d::Zero(), 1.0)); },
      "circular-wire names particle 2");
  expectRejected([&] { system.addConstraint(std::make_unique<LineConstraint>(5, Vector2d::Zero(), 0.0)); },
                 "line names particle 5");
  EXPECT_TRUE(system.forceObjects().empty());
  EXPECT_TRUE(system.constraints().empty());
}

// --- dynamics --------------------------------------------------------------------

TEST(ParticleSystem, PinnedParticleNeverMovesAndUnpinningRestoresItsMass) {
  ParticleSystem system = makePendulum();
  system.addForce(std::make_unique<MouseSpringForce>(0, Vector2d(1.0, 1.0), 50.0, 0.0));
  auto integrator = makeIntegrator("rk4");
  for (int step = 0; step < 50; ++step) system.step(*integrator, 0.01);
  EXPECT_EQ(system.position(0), Vector2d::Zero());
  EXPECT_EQ(system.velocity(0), Vector2d::Zero());

  system.setPinned(0, false);
  EXPECT_EQ(system.inverseMasses()[0], 1.0);
  system.setPinned(2, true);
  EXPECT_EQ(system.velocity(2), Vector2d::Zero()) << "pinning zeroes the velocity";
}

TEST(ParticleSystem, StepAdvancesTheClockAndMatchesTheIntegratorAlone) {
  ParticleSystem stepped = makePendulum(), direct = makePendulum();
  auto a = makeIntegrator("midpoint"), b = makeIntegrator("midpoint");
  for (int k = 0; k < 10; ++k) {
    stepped.step(*a, 0.02);
    b->step(direct, 0.02);  // no colliders: step adds only the clock
  }
  EXPECT_NEAR(stepped.time(), 0.2, 1e-15);
  EXPECT_EQ(stepped.positions(), direct.positions());
  EXPECT_EQ(stepped.velocities(), direct.velocities());
  EXPECT_EQ(stepped.contactsLastStep(), 0);
}

TEST(ParticleSystem, AccelerationIsInverseMassTimesForcesPlusConstraintForces) {
  ParticleSystem system = makePendulum();
  Eigen::VectorXd a;
  system.acceleration(system.positions(), system.velocities(), a);
  for (int i = 0; i < system.size(); ++i)
    EXPECT_LT((a.segment<2>(2 * i) - system.inverseMasses()[i] * system.forces().segment<2>(2 * i)).norm(),
              1e-14);
  EXPECT_EQ(a.segment<2>(0), Vector2d::Zero());
  // Particle 2 has no constraint: only gravity and the spring act on it.
  Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
  for (const auto& force : system.forceObjects()) force->apply(system.phase(), q);
  EXPECT_LT((system.forces().segment<2>(4) - q.segment<2>(4)).norm(), 1e-14);
  EXPECT_GT((system.forces().segment<2>(2) - q.segment<2>(2)).norm(), 1e-3) << "rod force on particle 1";
}

TEST(ParticleSystem, SnapshotRestoresStateAndTime) {
  ParticleSystem system = makePendulum();
  auto integrator = makeIntegrator("rk4");
  for (int k = 0; k < 5; ++k) system.step(*integrator, 0.01);
  const Snapshot saved = system.snapshot();
  for (int k = 0; k < 5; ++k) system.step(*integrator, 0.01);
  const Eigen::VectorXd x10 = system.positions();
  system.restore(saved);
  EXPECT_EQ(system.positions(), saved.x);
  EXPECT_EQ(system.time(), saved.time);
  // The warm start is reset on restore, so replaying gives the same result to
  // the solver's tolerance.
  for (int k = 0; k < 5; ++k) system.step(*integrator, 0.01);
  EXPECT_LT((system.positions() - x10).norm(), 1e-9);

  ParticleSystem other;
  other.addParticle(Vector2d::Zero(), 1.0);
  expectRejected([&] { other.restore(saved); }, "another size");
}

TEST(ParticleSystem, RemovedForceNoLongerActs) {
  ParticleSystem system;
  system.addParticle(Vector2d::Zero(), 1.0);
  Force& mouse = system.addForce(std::make_unique<MouseSpringForce>(0, Vector2d(1.0, 0.0), 4.0, 0.0));
  Eigen::VectorXd a;
  system.acceleration(system.positions(), system.velocities(), a);
  EXPECT_EQ(a[0], 4.0);
  system.removeForce(&mouse);
  system.acceleration(system.positions(), system.velocities(), a);
  EXPECT_EQ(a[0], 0.0);
  EXPECT_TRUE(system.forceObjects().empty());
}

// --- diagnostics ------------------------------------------------------------------

TEST(ParticleSystem, EnergiesSumKineticAndEveryPotential) {
  ParticleSystem system = makePendulum();
  system.setVelocity(2, Vector2d(0.0, 2.0));
  // Kinetic: ½·2·(1² + 0.75²) + ½·0.5·2² (the pinned particle has none).
  EXPECT_NEAR(system.kineticEnergy(), 1.5625 + 1.0, 1e-14);
  // Spring: ½·10·(0.5 − 0.4)²; gravity: −Σ m g·x over movable particles.
  const double spring = 0.05, gravity = -(2.0 * 9.81 * 0.4 + 0.5 * 9.81 * 0.4);
  EXPECT_NEAR(system.potentialEnergy(), spring + gravity, 1e-12);
  EXPECT_NEAR(system.totalEnergy(), 2.5625 + spring + gravity, 1e-12);
}

TEST(ParticleSystem, ConstraintErrorsInWorldAndRelativeUnits) {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 0.0), 1.0);
  system.addParticle(Vector2d(0.55, 0.0), 1.0);
  system.addParticle(Vector2d(0.0, 2.1), 1.0);
  system.addConstraint(std::make_unique<RodConstraint>(0, 1, 0.5, RodForm::Root));  // off by 0.05
  system.addConstraint(std::make_unique<CircularWireConstraint>(2, Vector2d::Zero(), 2.0));  // 0.1
  system.addConstraint(std::make_unique<LineConstraint>(0, Vector2d(0.0, -0.02), 0.0));  // 0.02
  EXPECT_NEAR(system.maxConstraintError(), 0.1, 1e-12);
  EXPECT_NEAR(system.maxRelativeConstraintError(), 0.1, 1e-12);  // rod 0.05/0.5; wire 0.1/2
  EXPECT_TRUE(system.finite());
  system.setPosition(1, Vector2d(system.position(1).x(), std::nan("")));
  EXPECT_FALSE(system.finite());
}

// The state is read-only through positions()/velocities(); the setters change
// exactly what they name and refuse a wrong size or index in one message.
TEST(ParticleSystem, StateSettersChangeWhatTheyNameAndRefuseBadSizes) {
  ParticleSystem system = makePendulum();
  const Eigen::VectorXd x0 = system.positions(), v0 = system.velocities();
  system.setPosition(1, Vector2d(0.25, -0.5));
  EXPECT_EQ(system.position(1), Vector2d(0.25, -0.5));
  EXPECT_EQ(system.position(0), x0.segment<2>(0));
  system.setVelocity(2, Vector2d(1.0, 2.0));
  EXPECT_EQ(system.velocity(2), Vector2d(1.0, 2.0));
  EXPECT_EQ(system.velocity(1), v0.segment<2>(2));
  system.setPositions(x0);
  system.setVelocities(v0);
  EXPECT_EQ(system.positions(), x0);
  EXPECT_EQ(system.velocities(), v0);
  test_support::expectRejected([&] { system.setPositions(Eigen::VectorXd::Zero(3)); }, "setPositions has 3 values");
  test_support::expectRejected([&] { system.setVelocities(Eigen::VectorXd::Zero(2)); }, "setVelocities has 2 values");
  test_support::expectRejected([&] { system.setPosition(system.size(), Vector2d::Zero()); }, "setPosition names particle");
  test_support::expectRejected([&] { system.setVelocity(-1, Vector2d::Zero()); }, "setVelocity names particle");
  EXPECT_EQ(system.positions(), x0);
}

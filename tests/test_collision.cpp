// Collisions: wall contact with restitution and friction, disc–disc impulses
// (momentum, restitution, pinned particles), and the grid broad phase against
// a brute-force pair count.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "particles/collision.h"
#include "particles/forces/gravity.h"
#include "particles/particle_system.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;
using Eigen::VectorXd;
using test_support::expectRejected;

namespace {

// A floor whose top face is y = 0.
Wall floorWall(double restitution, double friction = 0.0) {
  Wall wall;
  wall.min = Vector2d(-10.0, -1.0);
  wall.max = Vector2d(10.0, 0.0);
  wall.restitution = restitution;
  wall.friction = friction;
  return wall;
}

// The disc–disc state of two particles, resolved directly (no integration).
struct Pair {
  VectorXd x{4}, v{4}, inverseMass{2}, radius{2};
  std::vector<int> collidable{0, 1};
  Vector2d position(int i) const { return x.segment<2>(2 * i); }
  Vector2d velocity(int i) const { return v.segment<2>(2 * i); }
  int resolve(double restitution) {
    ParticleContacts contacts;
    contacts.restitution = restitution;
    return contacts.resolve(collidable, inverseMass, radius, x, v);
  }
};

}  // namespace

// --- walls -------------------------------------------------------------------

// Under constant gravity every integrator's velocity update is exact,
// v_impact = v_before + g dt, so the rebound ratio can be checked bounce by bounce.
TEST(WallContact, DroppedParticleReboundsWithRestitutionTimesImpactSpeed) {
  const double s = 0.6, radius = 0.05, dt = 0.01;
  const Vector2d g(0.0, -9.81);
  for (const char* name : {"euler", "symplectic-euler", "midpoint", "rk4"}) {
    SCOPED_TRACE(name);
    ParticleSystem system;
    system.addParticle(Vector2d(0.3, 1.0), 0.5);
    system.setCollidable(0, radius);
    system.addForce(std::make_unique<GravityForce>(g));
    system.addWall(floorWall(s));
    auto integrator = makeIntegrator(name);
    int bounces = 0;
    for (int step = 0; step < 400 && bounces < 3; ++step) {
      const double before = system.velocity(0).y();
      system.step(*integrator, dt);
      ASSERT_GE(system.position(0).y(), radius) << "inside the floor after step " << step;
      const double after = system.velocity(0).y();
      if (before <= 0.0 && after > 0.0) {  // this step hit the floor
        const double impact = before + g.y() * dt;
        EXPECT_NEAR(after / -impact, s, 0.01 * s) << "bounce " << bounces;
        EXPECT_DOUBLE_EQ(system.position(0).y(), radius) << "moved to the face, not beyond";
        ++bounces;
      }
    }
    EXPECT_EQ(bounces, 3);
    EXPECT_EQ(system.position(0).x(), 0.3) << "a vertical drop stays vertical";
  }
}

TEST(WallContact, NormalVelocityReflectsAndTangentialIsScaledByOneMinusFriction) {
  const std::vector<Wall> walls{floorWall(0.5, 0.25)};
  VectorXd x(2), v(2), w(1), r(1);
  x << 1.0, -0.01;
  v << 2.0, -3.0;
  w << 1.0;
  r << 0.0;
  resolveWallContacts(walls, w, r, x, v);
  EXPECT_EQ(x, Eigen::Vector2d(1.0, 0.0));
  EXPECT_DOUBLE_EQ(v[0], 1.5);
  EXPECT_DOUBLE_EQ(v[1], 1.5);
}

TEST(WallContact, LeavesByTheNearestFaceAndOnlyThatFaceReflects) {
  Wall box;
  box.min = Vector2d(0.0, 0.0);
  box.max = Vector2d(1.0, 2.0);
  box.restitution = 1.0;
  VectorXd x(2), v(2), w(1), r(1);
  x << 0.05, 0.9;  // nearest to the left face
  v << 1.0, -0.5;  // moving in, and down along the face
  w << 1.0;
  r << 0.0;
  resolveWallContacts({box}, w, r, x, v);
  EXPECT_EQ(x, Eigen::Vector2d(0.0, 0.9));
  EXPECT_EQ(v, Eigen::Vector2d(-1.0, -0.5));
}

TEST(WallContact, ParticleLeavingTheWallKeepsItsVelocity) {
  VectorXd x(2), v(2), w(1), r(1);
  x << 0.0, -0.02;
  v << 0.4, 0.7;  // already moving out of the floor
  w << 1.0;
  r << 0.0;
  resolveWallContacts({floorWall(0.3, 0.5)}, w, r, x, v);
  EXPECT_EQ(x, Eigen::Vector2d(0.0, 0.0));
  EXPECT_EQ(v, Eigen::Vector2d(0.4, 0.7));
}

TEST(WallContact, PinnedParticleIsNeverMoved) {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, -0.5), 1.0);  // inside the floor
  system.addParticle(Vector2d(0.5, -0.2), 1.0, Vector2d(0.0, -1.0));  // nearest the top face
  system.setPinned(0, true);
  system.addWall(floorWall(0.5));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  auto integrator = makeIntegrator("symplectic-euler");
  for (int step = 0; step < 20; ++step) system.step(*integrator, 0.01);
  EXPECT_EQ(system.position(0), Vector2d(0.0, -0.5));
  EXPECT_EQ(system.velocity(0), Vector2d::Zero());
  EXPECT_GE(system.position(1).y(), 0.0) << "the movable particle was pushed out";
}

// Disc contacts push the lower discs of a stack down; the floor must still have
// the last word, so that no disc ends a step inside it.
TEST(WallContact, StackedDiscsNeverEndAStepInsideTheFloor) {
  const double radius = 0.1;
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 0.1), 1.0);
  system.addParticle(Vector2d(0.0, 0.35), 1.0);
  system.addParticle(Vector2d(0.01, 0.6), 1.0);
  for (int i = 0; i < 3; ++i) system.setCollidable(i, radius);
  system.addWall(floorWall(0.3));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  auto integrator = makeIntegrator("symplectic-euler");
  int contacts = 0;
  for (int step = 0; step < 300; ++step) {
    system.step(*integrator, 0.01);
    contacts += system.contactsLastStep();
    for (int i = 0; i < 3; ++i)
      ASSERT_GE(system.position(i).y(), radius) << "disc " << i << " inside the floor after step " << step;
  }
  EXPECT_GT(contacts, 0);
}

// --- particle–particle ---------------------------------------------------------

TEST(ParticleContacts, HeadOnEqualMassesWithUnitRestitutionExchangeVelocities) {
  ParticleSystem system;
  system.addParticle(Vector2d(-0.5, 0.2), 1.3, Vector2d(1.0, 0.0));
  system.addParticle(Vector2d(0.5, 0.2), 1.3, Vector2d(-0.4, 0.0));
  system.setCollidable(0, 0.1);
  system.setCollidable(1, 0.1);
  system.particleContacts().restitution = 1.0;
  auto integrator = makeIntegrator("symplectic-euler");
  int contacts = 0;
  for (int step = 0; step < 100; ++step) {
    system.step(*integrator, 0.01);
    contacts += system.contactsLastStep();
  }
  EXPECT_GE(contacts, 1);
  EXPECT_NEAR((system.velocity(0) - Vector2d(-0.4, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((system.velocity(1) - Vector2d(1.0, 0.0)).norm(), 0.0, 1e-12);
}

// An oblique contact of masses 1 and 3 with e = 0.6: momentum and the centre of
// mass are kept, the relative normal velocity becomes −e times itself, and the
// tangential relative velocity is untouched.
TEST(ParticleContacts, UnequalMassesConserveMomentumAndScaleRelativeNormalVelocityByE) {
  const double e = 0.6, m0 = 1.0, m1 = 3.0;
  Pair pair;
  pair.x << 0.0, 0.0, 0.15, 0.05;
  pair.v << 1.0, 0.2, -0.5, 0.1;
  pair.inverseMass << 1.0 / m0, 1.0 / m1;
  pair.radius << 0.1, 0.1;
  const Vector2d n = (pair.position(0) - pair.position(1)).normalized();
  const Vector2d momentum = m0 * pair.velocity(0) + m1 * pair.velocity(1);
  const Vector2d centre = m0 * pair.position(0) + m1 * pair.position(1);
  const Vector2d relative = pair.velocity(0) - pair.velocity(1);

  EXPECT_EQ(pair.resolve(e), 1);

  const Vector2d relativeAfter = pair.velocity(0) - pair.velocity(1);
  EXPECT_LT((m0 * pair.velocity(0) + m1 * pair.velocity(1) - momentum).norm(), 1e-14);
  EXPECT_LT((m0 * pair.position(0) + m1 * pair.position(1) - centre).norm(), 1e-14);
  ASSERT_LT(relative.dot(n), 0.0) << "the test needs an approaching pair";
  EXPECT_NEAR(relativeAfter.dot(n), -e * relative.dot(n), 1e-14);
  const Vector2d t(-n.y(), n.x());
  EXPECT_NEAR(relativeAfter.dot(t), relative.dot(t), 1e-14);
  EXPECT_NEAR((pair.position(0) - pair.position(1)).norm(), 0.2, 1e-14) << "separated to touching";
}

TEST(ParticleContacts, PinnedParticleIsNeverMoved) {
  const double e = 0.5;
  Pair pair;
  pair.x << 0.0, 0.0, 0.12, 0.09;  // distance 0.15, radii sum 0.2
  pair.v << 0.0, 0.0, -1.0, 0.0;
  pair.inverseMass << 0.0, 1.0;
  pair.radius << 0.1, 0.1;
  const Vector2d n(0.8, 0.6);  // from the pinned disc to the movable one
  EXPECT_EQ(pair.resolve(e), 1);
  EXPECT_EQ(pair.position(0), Vector2d::Zero());
  EXPECT_EQ(pair.velocity(0), Vector2d::Zero());
  EXPECT_NEAR((pair.position(1) - 0.2 * n).norm(), 0.0, 1e-14) << "the movable disc takes all the overlap";
  EXPECT_NEAR(pair.velocity(1).dot(n), -e * Vector2d(-1.0, 0.0).dot(n), 1e-14);

  // Two pinned discs overlap and stay where they are.
  pair.inverseMass << 0.0, 0.0;
  pair.x << 0.0, 0.0, 0.05, 0.0;
  pair.v.setZero();
  EXPECT_EQ(pair.resolve(e), 0);
  EXPECT_EQ(pair.position(1), Vector2d(0.05, 0.0));
}

// Random discs (some pinned, coordinates of both signs, radii from 0.02 to
// 0.05) placed as isolated singles and overlapping pairs, far enough apart that
// resolving one pair cannot create or remove another contact: the grid must
// find exactly the pairs an O(n²) search finds.
TEST(ParticleContacts, GridBroadPhaseFindsTheSameContactsAsBruteForce) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0), radiusOf(0.02, 0.05), unit(0.0, 1.0);
  const double margin = 0.06;  // > the largest push-out, 0.25 · (0.05 + 0.05) per disc
  std::vector<Vector2d> centres, positions;
  std::vector<double> extents, radii;
  for (int attempt = 0; attempt < 20000 && positions.size() < 600; ++attempt) {
    const Vector2d c(coordinate(rng), coordinate(rng));
    const double r0 = radiusOf(rng), r1 = radiusOf(rng);
    const bool pair = unit(rng) < 0.5;
    const double distance = (0.75 + 0.2 * unit(rng)) * (r0 + r1);
    const double extent = pair ? distance / 2 + std::max(r0, r1) : r0;
    bool clear = true;
    for (std::size_t k = 0; k < centres.size() && clear; ++k)
      clear = (centres[k] - c).norm() > extents[k] + extent + margin;
    if (!clear) continue;
    centres.push_back(c);
    extents.push_back(extent);
    if (pair) {
      const double angle = 2.0 * 3.14159265358979 * unit(rng);
      const Vector2d half = 0.5 * distance * Vector2d(std::cos(angle), std::sin(angle));
      positions.push_back(c + half), radii.push_back(r0);
      positions.push_back(c - half), radii.push_back(r1);
    } else {
      positions.push_back(c), radii.push_back(r0);
    }
  }
  const int n = static_cast<int>(positions.size());
  ASSERT_GT(n, 300);
  VectorXd x(2 * n), v = VectorXd::Zero(2 * n), w(n), radius(n);
  std::vector<int> collidable(n);
  for (int i = 0; i < n; ++i) {
    x.segment<2>(2 * i) = positions[i];
    w[i] = unit(rng) < 0.2 ? 0.0 : 1.0 / (0.5 + unit(rng));
    radius[i] = radii[i];
    collidable[i] = i;
  }

  int bruteForce = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (w[i] + w[j] > 0.0 && (positions[i] - positions[j]).norm() < radius[i] + radius[j]) ++bruteForce;
  ASSERT_GT(bruteForce, 50);

  ParticleContacts contacts;
  EXPECT_EQ(contacts.resolve(collidable, w, radius, x, v), bruteForce);
  // After resolution no movable pair overlaps any more.
  int remaining = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (w[i] + w[j] > 0.0 &&
          (x.segment<2>(2 * i) - x.segment<2>(2 * j)).norm() < radius[i] + radius[j] - 1e-12)
        ++remaining;
  EXPECT_EQ(remaining, 0);
}

// --- parameters ----------------------------------------------------------------

TEST(CollisionParameters, RejectedWithTheirName) {
  ParticleSystem system;
  auto addWall = [&](double restitution, double friction) {
    return [&system, restitution, friction] { system.addWall(floorWall(restitution, friction)); };
  };
  expectRejected(addWall(-0.1, 0.0), "wall restitution");
  expectRejected(addWall(1.5, 0.0), "wall restitution");
  expectRejected(addWall(1.5, 0.0), "got 1.5");
  expectRejected(addWall(std::nan(""), 0.0), "wall restitution");
  expectRejected(addWall(0.5, -0.2), "wall friction");
  expectRejected(addWall(0.5, 1.2), "wall friction");
  expectRejected(addWall(0.5, std::nan("")), "wall friction");
  Wall inverted = floorWall(0.5);
  std::swap(inverted.min, inverted.max);
  expectRejected([&] { system.addWall(inverted); }, "wall max");
  EXPECT_TRUE(system.walls().empty());
}

TEST(CollisionParameters, ParticleRestitutionOutsideUnitIntervalIsRejected) {
  for (double restitution : {-0.5, 1.5, std::nan("")}) {
    ParticleSystem system;
    system.addParticle(Vector2d(0.0, 0.0), 1.0);
    system.addParticle(Vector2d(0.15, 0.0), 1.0, Vector2d(-1.0, 0.0));
    system.setCollidable(0, 0.1);
    system.setCollidable(1, 0.1);
    system.particleContacts().restitution = restitution;
    auto integrator = makeIntegrator("rk4");
    expectRejected([&] { system.step(*integrator, 0.01); }, "restitution");
  }
}

TEST(ParticleContacts, FarFlungAndNonFiniteParticlesDoNotBreakTheBroadPhase) {
  // An exploded simulation leaves particles at huge or non-finite positions;
  // the grid must neither overflow its cell indices nor lose the ordinary pair.
  Eigen::VectorXd x(8), v = Eigen::VectorXd::Zero(8), w = Eigen::VectorXd::Ones(4);
  Eigen::VectorXd r = Eigen::VectorXd::Constant(4, 0.1);
  x << 0.0, 0.0, 0.15, 0.0, 1e300, -1e300, std::nan(""), 0.0;
  ParticleContacts contacts;
  EXPECT_EQ(contacts.resolve({0, 1, 2, 3}, w, r, x, v), 1);
  EXPECT_NEAR((x.segment<2>(0) - x.segment<2>(2)).norm(), 0.2, 1e-12);
}

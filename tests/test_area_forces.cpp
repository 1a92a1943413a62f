// The forces on an area: the ring's signed area and its derivatives against
// finite differences; the face-area floor (zero above it, f = −∂E/∂x, exact
// and definite Jacobians, an inverted face turned back under every
// integrator, xpbd's one-sided projection); the gas pressure of a closed ring
// (f = −∂E/∂x, Jacobians, Boyle's and Laplace's laws at the equilibrium every
// integrator reaches).
#include <cmath>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "particles/constants.h"
#include "particles/forces/drag.h"
#include "particles/forces/face_area.h"
#include "particles/forces/polygon_area.h"
#include "particles/forces/pressure.h"
#include "particles/forces/spring.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "xpbd/area.h"
#include "test_support.h"

using namespace particles;
using Eigen::Vector2d;
using Eigen::VectorXd;
using test_support::centralGradient;
using test_support::centralJacobian;
using test_support::denseFromTriplets;
using test_support::expectJacobiansMatchFiniteDifference;
using test_support::expectRejected;
using test_support::forceAt;
using test_support::randomVector;

namespace {

ParticleSystem particlesAt(const std::vector<Vector2d>& positions, double mass = 1.0) {
  ParticleSystem system;
  for (const Vector2d& p : positions) system.addParticle(p, mass);
  return system;
}

// f = −∂E/∂x at v = 0 and random positions.
void expectForceIsMinusEnergyGradient(const ParticleSystem& system, const Force& force, std::mt19937& rng) {
  const VectorXd v = VectorXd::Zero(2 * system.size());
  for (int trial = 0; trial < 30; ++trial) {
    const VectorXd x = randomVector(2 * system.size(), rng);
    const VectorXd f = forceAt(force, system.phase(x, v));
    const VectorXd grad = centralGradient([&](const VectorXd& y) { return force.potential(system.phase(y, v)); }, x);
    EXPECT_LT((f + grad).norm(), 1e-6 * (1.0 + f.norm())) << "f = " << f.transpose() << "\n−∂E/∂x = " << -grad.transpose();
  }
}

// The definite Jacobian ∂f/∂x is symmetric with no positive eigenvalue, at random positions.
void expectDefiniteJacobianIsNegativeSemiDefinite(const ParticleSystem& system, const Force& force, std::mt19937& rng) {
  const VectorXd v = VectorXd::Zero(2 * system.size());
  for (int trial = 0; trial < 30; ++trial) {
    const VectorXd x = randomVector(2 * system.size(), rng);
    Triplets dfdx, dfdv;
    force.addDefiniteJacobians(system.phase(x, v), dfdx, dfdv);
    const Eigen::MatrixXd K = denseFromTriplets(dfdx, 2 * system.size());
    EXPECT_LT((K - K.transpose()).norm(), 1e-12 * (1.0 + K.norm()));
    EXPECT_LE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(K).eigenvalues().maxCoeff(), 1e-9 * (1.0 + K.norm()));
  }
}

// A unit square's corners, counter-clockwise from the origin.
std::vector<Vector2d> unitSquare() { return {{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}; }

}  // namespace

// --- the ring's area -----------------------------------------------------------

TEST(RingArea, IsPositiveCounterClockwiseAndItsDerivativesMatchFiniteDifference) {
  const ParticleSystem square = particlesAt(unitSquare());
  EXPECT_DOUBLE_EQ(ringArea(square.positions(), {0, 1, 2, 3}), 1.0);
  EXPECT_DOUBLE_EQ(ringArea(square.positions(), {3, 2, 1, 0}), -1.0);
  EXPECT_DOUBLE_EQ(ringArea(square.positions(), {0, 1, 2}), 0.5);

  std::mt19937 rng(3);
  const std::vector<int> ring = {4, 0, 2, 1, 3};  // any order of any particles
  for (int trial = 0; trial < 10; ++trial) {
    const VectorXd x = randomVector(10, rng);
    std::vector<Vector2d> gradient;
    const double area = ringAreaGradient(x, ring, gradient);
    EXPECT_DOUBLE_EQ(area, ringArea(x, ring));
    const VectorXd fd = centralGradient([&](const VectorXd& y) { return ringArea(y, ring); }, x);
    for (std::size_t k = 0; k < ring.size(); ++k)
      EXPECT_LT((gradient[k] - fd.segment<2>(2 * ring[k])).norm(), 1e-8) << "corner " << k;
    // The Hessian's blocks against differences of the gradient.
    const Eigen::MatrixXd H = centralJacobian(
        [&](const VectorXd& y) {
          std::vector<Vector2d> g;
          ringAreaGradient(y, ring, g);
          VectorXd out = VectorXd::Zero(10);
          for (std::size_t k = 0; k < ring.size(); ++k) out.segment<2>(2 * ring[k]) = g[k];
          return out;
        },
        x);
    const int n = static_cast<int>(ring.size());
    for (int k = 0; k < n; ++k)
      for (int l = 0; l < n; ++l)
        EXPECT_LT((ringAreaHessianBlock(k, l, n) - H.block<2, 2>(2 * ring[k], 2 * ring[l])).norm(), 1e-8)
            << "block " << k << ", " << l;
  }
}

TEST(RingArea, RingsAreCheckedNamingTheForce) {
  expectRejected([] { requireRing("pressure force", {0, 1}); }, "at least 3 particles");
  expectRejected([] { requireRing("pressure force", {0, 1, 0}); }, "names a particle twice");
}

// --- the face-area floor ----------------------------------------------------

TEST(FaceAreaForce, NothingAboveTheFloor) {
  ParticleSystem system = particlesAt(unitSquare());
  const FaceAreaForce force({{{0, 1, 2, 3}, 1.0}}, 50.0, 0.5);
  EXPECT_EQ(forceAt(force, system.phase()).norm(), 0.0);
  EXPECT_EQ(force.potential(system.phase()), 0.0);
  // Sheared to 60° (area 0.5) and just past it.
  system.setPosition(2, Vector2d(1.0 + std::sqrt(3.0), 0.5));
  system.setPosition(3, Vector2d(std::sqrt(3.0), 0.5));
  EXPECT_NEAR(ringArea(system.positions(), {0, 1, 2, 3}), 0.5, 1e-15);
  EXPECT_LT(forceAt(force, system.phase()).norm(), 1e-12);
  system.setPosition(2, Vector2d(1.0 + std::sqrt(3.0), 0.4));
  system.setPosition(3, Vector2d(std::sqrt(3.0), 0.4));
  const VectorXd f = forceAt(force, system.phase());
  // C = 0.4 − 0.5: each corner pushed with 50 · 0.1 · ∂A/∂x_k, which opens the
  // face; corner 3: ∂A/∂x₃ = ½ P (x₂ − x₀) = ½ (−0.4, 1 + √3).
  EXPECT_NEAR(f[6], 5.0 * 0.5 * -0.4, 1e-12);
  EXPECT_NEAR(f[7], 5.0 * 0.5 * (1.0 + std::sqrt(3.0)), 1e-12);
  EXPECT_NEAR(force.potential(system.phase()), 0.5 * 50.0 * 1.0 * 0.01, 1e-12);
}

TEST(FaceAreaForce, ForceIsMinusEnergyGradientAndJacobiansMatchFiniteDifference) {
  std::mt19937 rng(11);
  // Random corners in [−1, 1]²: areas of either sign, most of them below a
  // floor of 0.9 of A₀ = 1.5, some above.
  const ParticleSystem system = particlesAt(std::vector<Vector2d>(7, Vector2d::Zero()));
  const FaceAreaForce force({{{0, 1, 2, 3}, 1.5}, {{3, 4, 5}, 0.7}, {{6, 2, 5, 1}, 2.0}}, 3.0, 0.9);
  expectForceIsMinusEnergyGradient(system, force, rng);
  expectJacobiansMatchFiniteDifference(system, force, rng);
  expectDefiniteJacobianIsNegativeSemiDefinite(system, force, rng);
}

TEST(FaceAreaForce, FieldsAreValidatedAndATornSideDropsItsFace) {
  expectRejected([] { FaceAreaForce({{{0, 1, 2}, 1.0}}, -1.0, 0.5); }, "stiffness");
  expectRejected([] { FaceAreaForce({{{0, 1, 2}, 1.0}}, 1.0, 1.5); }, "floor");
  expectRejected([] { FaceAreaForce({{{0, 1, 2}, 1.0}, {{0, 1, 2}, 0.0}}, 1.0, 0.5); }, "face 1 rest area");
  expectRejected([] { FaceAreaForce({{{0, 1}, 1.0}}, 1.0, 0.5); }, "at least 3");
  FaceAreaForce force({{{0, 1, 2, 3}, 1.0}, {{2, 3, 4}, 1.0}}, 1.0, 0.5);
  EXPECT_FALSE(force.dropLinks(LinkSet({{0, 2}})));  // a diagonal is no side
  EXPECT_TRUE(force.dropLinks(LinkSet({{0, 3}})));   // the closing side 3–0
  ASSERT_EQ(force.faces().size(), 1u);
  EXPECT_EQ(force.faces()[0].ring, (std::vector<int>{2, 3, 4}));
}

// A square of four particles joined by its four sides and two diagonals
// (springs at rest either way round) turned over: without the floor it rests
// inverted; with it, every integrator turns it back (the floor's energy at
// A = −A₀ exceeds the springs' barrier to flattening it), and the face ends
// the right way round at rest.
TEST(FaceAreaForce, AnInvertedFaceTurnsBackUnderEveryIntegrator) {
  const double r = 0.05, ks = 200.0, m = 0.005;
  auto build = [&](double floorStiffness) {
    // Mirrored: corners clockwise.
    auto system = std::make_unique<ParticleSystem>();
    for (const Vector2d& p : unitSquare()) system->addParticle(r * Vector2d(-p.x(), p.y()), m);
    const int sides[][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
    for (const auto& s : sides) system->addForce(std::make_unique<SpringForce>(s[0], s[1], r, ks, 0.5));
    system->addForce(std::make_unique<SpringForce>(0, 2, std::sqrt(2.0) * r, ks, 0.5));
    system->addForce(std::make_unique<SpringForce>(1, 3, std::sqrt(2.0) * r, ks, 0.5));
    system->addForce(std::make_unique<DragForce>(0.01));
    if (floorStiffness > 0.0)
      system->addForce(std::make_unique<FaceAreaForce>(std::vector<AreaFace>{{{0, 1, 2, 3}, r * r}}, floorStiffness, 0.5));
    return system;
  };
  // A nudge off the symmetric state, so that nothing balances on a saddle.
  auto nudge = [&](ParticleSystem& s) { s.setPosition(0, s.position(0) + Vector2d(1e-4, 3e-4)); };
  {
    auto without = build(0.0);
    nudge(*without);
    const auto integrator = makeIntegrator("rk4");
    for (int step = 0; step < 10000; ++step) without->step(*integrator, 1e-4);
    EXPECT_LT(ringArea(without->positions(), {0, 1, 2, 3}), -0.9 * r * r);
  }
  for (const IntegratorInfo& info : integratorTable()) {
    SCOPED_TRACE(info.name);
    auto system = build(4.0 * ks);
    nudge(*system);
    const auto integrator = makeIntegrator(info.name);
    // dt = 0.1 ms: explicit Euler is stable on these damped springs below ω dt = 2ζ.
    for (int step = 0; step < 10000; ++step) ASSERT_EQ(system->step(*integrator, 1e-4).failure, StepFailure::None);
    EXPECT_GT(ringArea(system->positions(), {0, 1, 2, 3}), 0.9 * r * r);
    EXPECT_TRUE(system->finite());
  }
}

TEST(XpbdArea, ProjectsAFaceBelowItsFloorUpToItAndLeavesOneAboveAlone) {
  // A triangle of area 0.1 with A₀ = 1 and floor 0.5; hard (α = 0): one
  // projection restores C = 0 to first order, a few exactly.
  ParticleSystem system = particlesAt({{0.0, 0.0}, {1.0, 0.0}, {0.0, 0.2}});
  VectorXd x = system.positions();
  const VectorXd w = VectorXd::Ones(3);
  CompliantArea c;
  c.ring = {0, 1, 2};
  c.restArea = 1.0;
  c.floor = 0.5;
  double lambda = 0.0;
  for (int k = 0; k < 5; ++k) projectArea(c, w, x, lambda);
  EXPECT_NEAR(ringArea(x, c.ring), 0.5, 1e-9);
  EXPECT_GT(lambda, 0.0);
  // Above the floor, never pushed this substep: untouched.
  VectorXd above = particlesAt({{0.0, 0.0}, {2.0, 0.0}, {0.0, 2.0}}).positions();
  const VectorXd before = above;
  double none = 0.0;
  projectArea(c, w, above, none);
  EXPECT_EQ(above, before);
  EXPECT_EQ(none, 0.0);
}

// --- the gas pressure of a ring ---------------------------------------------

TEST(PressureForce, ForceIsMinusEnergyGradientAndJacobiansMatchFiniteDifference) {
  std::mt19937 rng(5);
  const ParticleSystem system = particlesAt(std::vector<Vector2d>(6, Vector2d::Zero()));
  // A₀ = 0.05: random rings have areas above and below A₀/10, both signs.
  const PressureForce force({0, 1, 2, 3, 4, 5}, 0.05, 2.0);
  expectForceIsMinusEnergyGradient(system, force, rng);
  expectJacobiansMatchFiniteDifference(system, force, rng);
  expectDefiniteJacobianIsNegativeSemiDefinite(system, force, rng);
}

TEST(PressureForce, PushesOutwardWithBoylesPressureAndHoldsItBelowATenth) {
  ParticleSystem system = particlesAt(unitSquare());
  const PressureForce force({0, 1, 2, 3}, 0.5, 3.0);  // p₀ = 3 at A₀ = 0.5: p = 1.5 at A = 1
  VectorXd f = forceAt(force, system.phase());
  // Corner 2 at (1, 1): ∂A/∂x = ½ P (x₁ − x₃) = ½ (1, 1).
  EXPECT_NEAR(f[4], 1.5 * 0.5, 1e-14);
  EXPECT_NEAR(f[5], 1.5 * 0.5, 1e-14);
  EXPECT_NEAR(f.sum(), 0.0, 1e-14);  // no net force
  EXPECT_NEAR(force.potential(system.phase()), -3.0 * 0.5 * std::log(2.0), 1e-14);
  EXPECT_DOUBLE_EQ(force.law().at(0.01), force.law().at(0.05));  // held at 10 p₀ below A₀/10
  EXPECT_DOUBLE_EQ(force.law().at(0.05), 30.0);
  expectRejected([] { PressureForce({0, 1, 2}, 0.0, 1.0); }, "rest area");
  expectRejected([] { PressureForce({0, 1, 2}, 1.0, -1.0); }, "pressure");
  PressureForce torn({0, 1, 2, 3}, 0.5, 3.0);
  EXPECT_TRUE(torn.dropLinks(LinkSet({{3, 0}})));
  EXPECT_EQ(forceAt(torn, system.phase()).norm(), 0.0);
}

// The circumradius R at which a regular N-gon of springs (k_s, rest r)
// holds a gas of p₀ at A₀ (below), by bisection.
double ringEquilibriumRadius(int N, double r, double ks, double p0, double A0) {
  auto balance = [&](double R) {
    const double A = 0.5 * N * R * R * std::sin(2.0 * kPi / N);
    const double T = ks * (2.0 * R * std::sin(kPi / N) - r);
    return p0 * A0 / A - T / (R * std::cos(kPi / N));
  };
  double lo = r / (2.0 * std::sin(kPi / N)), hi = 10.0 * lo;  // no tension at lo; the springs win at hi
  for (int k = 0; k < 200; ++k) (balance(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

// A ring of N particles joined by springs (k_s, rest r) with a gas inside
// (p₀ at A₀) settles as a regular N-gon whose circumradius R balances the
// gas against the springs' tension T = k_s (l − r), l = 2 R sin(π/N): the
// pressure on a corner p |∂A/∂x| = p R sin(2π/N) against the springs'
// inward pull 2 T sin(π/N), i.e. Laplace's law for the polygon,
//   p = T / (R cos(π/N)),   with Boyle's p = p₀ A₀ / A,  A = ½ N R² sin(2π/N).
// Every integrator reaches that R from the ring at its rest size.
TEST(PressureForce, ARingSettlesWhereBoylesAndLaplacesLawsMeetUnderEveryIntegrator) {
  const int N = 12;
  const double r = 0.05, ks = 50.0, m = 0.01, p0 = 20.0;
  const double R0 = r / (2.0 * std::sin(kPi / N));
  const double A0 = 0.5 * N * R0 * R0 * std::sin(2.0 * kPi / N);
  const double R = ringEquilibriumRadius(N, r, ks, p0, A0);
  ASSERT_GT(R, 1.1 * R0);  // the gas stretches the ring visibly

  for (const IntegratorInfo& info : integratorTable()) {
    SCOPED_TRACE(info.name);
    ParticleSystem system;
    std::vector<int> ring;
    for (int k = 0; k < N; ++k) {
      const double a = 2.0 * kPi * k / N;
      ring.push_back(system.addParticle(R0 * Vector2d(std::cos(a), std::sin(a)), m));
    }
    for (int k = 0; k < N; ++k) system.addForce(std::make_unique<SpringForce>(k, (k + 1) % N, r, ks, 0.05));
    system.addForce(std::make_unique<PressureForce>(ring, A0, p0));
    system.addForce(std::make_unique<DragForce>(0.05));
    IntegratorSettings settings;
    settings.dopri5.tolerance = 1e-10;
    settings.xpbd.substeps = 50;
    const auto integrator = makeIntegrator(info.name, settings);
    // 6 s at 0.2 ms (explicit Euler needs ω dt < 2ζ): the drag's 5/s leaves e^−30 of the start.
    for (int step = 0; step < 30000; ++step) ASSERT_EQ(system.step(*integrator, 2e-4).failure, StepFailure::None);
    for (int k = 0; k < N; ++k) EXPECT_NEAR(system.position(k).norm(), R, 1e-3 * R) << "corner " << k;
    EXPECT_LT(system.velocities().norm(), 1e-6);
  }
}

// Velocity Verlet, backward Euler with the
// constraints in its solve, adaptive RK4 — and the force Jacobians the
// implicit step relies on.
#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "particles/constants.h"
#include "particles/constraints/circular_wire.h"
#include "particles/constraints/rod.h"
#include "particles/forces/angular_spring.h"
#include "particles/forces/drag.h"
#include "particles/forces/gravity.h"
#include "particles/forces/mouse_spring.h"
#include "particles/forces/spring.h"
#include "integrators/implicit_euler.h"
#include "particles/particle_system.h"
#include "scenes/cloth.h"
#include "scenes/pendulum.h"
#include "scenes/test_chain.h"
#include "oscillator_fixture.h"

using namespace particles;
using Eigen::Vector2d;

namespace {

// The oscillator at ω = 1 rad/s, swinging ±0.5 about its rest length of 1,
// with a damper of k_d = `damping` (the closed form covers it).
test_support::Oscillator oscillator(double damping = 0.0) {
  test_support::Oscillator o;
  o.params.stiffness = 1.0;
  o.params.damping = damping;
  o.params.stretch = 0.5;
  return o;
}

// The order of the scheme's global error at T = 2 s, dt halving from T/20 to T/320.
double fittedOrder(const std::string& scheme, const test_support::Oscillator& o) {
  return o.measureOrder(scheme, 2.0, {20, 40, 80, 160, 320}).order;
}

}  // namespace

TEST(Verlet, PredictedVelocityKeepsSecondOrderWithDamping) {
  const double order = fittedOrder("verlet", oscillator(0.5));
  RecordProperty("fitted_order", std::to_string(order));
  EXPECT_NEAR(order, 2.0, 0.3);
}

TEST(Rattle, PredictedVelocityKeepsSecondOrderWithDamping) {
  const double order = fittedOrder("rattle", oscillator(0.5));
  RecordProperty("fitted_order", std::to_string(order));
  EXPECT_NEAR(order, 2.0, 0.3);
}

// Energy of the undamped oscillator over 10⁴ steps of dt = 0.01 (ω = 1, 16 periods).
std::vector<double> energyHistory(const std::string& scheme) {
  ParticleSystem system = oscillator().build();
  auto integrator = makeIntegrator(scheme);
  std::vector<double> energy{system.totalEnergy()};
  for (int k = 0; k < 10000; ++k) {
    system.step(*integrator, 0.01);
    energy.push_back(system.totalEnergy());
  }
  return energy;
}

TEST(Verlet, EnergyErrorStaysBounded) {
  const std::vector<double> e = energyHistory("verlet");
  double early = 0.0, late = 0.0;  // worst error in the first and the last 1000 steps
  for (int k = 0; k <= 1000; ++k) early = std::max(early, std::abs(e[k] - e[0]));
  for (int k = 9000; k <= 10000; ++k) late = std::max(late, std::abs(e[k] - e[0]));
  EXPECT_LT(late, 1.5 * early);    // no drift
  EXPECT_LT(late, 1e-4 * e[0]);    // O(h²) oscillation only
}

TEST(ExplicitEuler, EnergyGrows) {
  const std::vector<double> e = energyHistory("euler");
  EXPECT_GT(e.back(), 2.0 * e.front());  // (1 + h²ω²)^N = e¹
  for (std::size_t k = 1; k < e.size(); ++k) ASSERT_GE(e[k], e[k - 1] * (1 - 1e-12));
}

TEST(ImplicitEuler, EnergyDecays) {
  const std::vector<double> e = energyHistory("implicit-euler");
  EXPECT_LT(e.back(), 0.5 * e.front());  // (1 + h²ω²)^−N = e⁻¹
  for (std::size_t k = 1; k < e.size(); ++k) ASSERT_LE(e[k], e[k - 1] * (1 + 1e-12));
}

// --- force Jacobians ------------------------------------------------------

namespace {

// Dense ∂f/∂x, ∂f/∂v of a force from its triplets, and the same by central
// differences of Force::apply.
struct DenseJacobians { Eigen::MatrixXd dfdx, dfdv; };

DenseJacobians analytic(const Force& force, const ParticleSystem& system, bool definite) {
  Triplets tx, tv;
  if (definite) force.addDefiniteJacobians(system.phase(), tx, tv);
  else force.addJacobians(system.phase(), tx, tv);
  const int dofs = 2 * system.size();
  Eigen::SparseMatrix<double> X(dofs, dofs), V(dofs, dofs);
  X.setFromTriplets(tx.begin(), tx.end());
  V.setFromTriplets(tv.begin(), tv.end());
  return {Eigen::MatrixXd(X), Eigen::MatrixXd(V)};
}

DenseJacobians finiteDifference(const Force& force, const ParticleSystem& system) {
  const int dofs = 2 * system.size();
  DenseJacobians J{Eigen::MatrixXd(dofs, dofs), Eigen::MatrixXd(dofs, dofs)};
  const double h = 1e-6;
  auto f = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
    Eigen::VectorXd out = Eigen::VectorXd::Zero(dofs);
    force.apply(system.phase(x, v), out);
    return out;
  };
  for (int c = 0; c < dofs; ++c) {
    Eigen::VectorXd xp = system.positions(), xm = xp, vp = system.velocities(), vm = vp;
    xp[c] += h, xm[c] -= h, vp[c] += h, vm[c] -= h;
    J.dfdx.col(c) = (f(xp, system.velocities()) - f(xm, system.velocities())) / (2 * h);
    J.dfdv.col(c) = (f(system.positions(), vp) - f(system.positions(), vm)) / (2 * h);
  }
  return J;
}

// Three particles at random places with random velocities (particle 3 pinned
// when asked, to check that forces still report their full Jacobian there).
std::unique_ptr<ParticleSystem> randomTriple(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto system = std::make_unique<ParticleSystem>();
  for (int i = 0; i < 3; ++i)
    system->addParticle(Vector2d(u(rng), u(rng)), 1.0 + 0.5 * (u(rng) + 1.0), Vector2d(u(rng), u(rng)));
  return system;
}

void expectJacobiansMatchFiniteDifference(const std::function<std::unique_ptr<Force>()>& make) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 30; ++trial) {
    auto system = randomTriple(rng);
    Force& force = system->addForce(make());
    ASSERT_TRUE(force.hasJacobians()) << force.type();
    const DenseJacobians a = analytic(force, *system, false), fd = finiteDifference(force, *system);
    const double scale = 1.0 + fd.dfdx.cwiseAbs().maxCoeff() + fd.dfdv.cwiseAbs().maxCoeff();
    EXPECT_LT((a.dfdx - fd.dfdx).cwiseAbs().maxCoeff(), 1e-6 * scale) << force.type() << " dfdx";
    EXPECT_LT((a.dfdv - fd.dfdv).cwiseAbs().maxCoeff(), 1e-6 * scale) << force.type() << " dfdv";
    // The definite approximation used by the implicit step: symmetric, and
    // negative semi-definite so that M − h D − h² K is positive definite.
    const DenseJacobians d = analytic(force, *system, true);
    for (const Eigen::MatrixXd* m : {&d.dfdx, &d.dfdv}) {
      EXPECT_LT((*m - m->transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale) << force.type();
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(*m);
      EXPECT_LT(eig.eigenvalues().maxCoeff(), 1e-9 * scale) << force.type();
    }
  }
}

}  // namespace

TEST(ForceJacobians, SpringMatchesFiniteDifference) {
  // Random rest length: stretched and compressed springs alike.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> rest(0.1, 2.0);
  expectJacobiansMatchFiniteDifference(
      [&] { return std::make_unique<SpringForce>(0, 2, rest(rng), 7.0, 0.8); });
}

TEST(ForceJacobians, AngularSpringMatchesFiniteDifference) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> angle(-3.0, 3.0);
  expectJacobiansMatchFiniteDifference(
      [&] { return std::make_unique<AngularSpringForce>(0, 1, 2, angle(rng), 3.0, 0.7); });
}

TEST(ForceJacobians, DragMatchesFiniteDifference) {
  expectJacobiansMatchFiniteDifference([] { return std::make_unique<DragForce>(0.9); });
}

TEST(ForceJacobians, GravityMatchesFiniteDifference) {
  expectJacobiansMatchFiniteDifference([] { return std::make_unique<GravityForce>(Vector2d(0.3, -9.8)); });
}

TEST(ForceJacobians, MouseSpringMatchesFiniteDifference) {
  expectJacobiansMatchFiniteDifference(
      [] { return std::make_unique<MouseSpringForce>(1, Vector2d(0.2, 0.4), 5.0, 0.6); });
}

// --- the implicit step with constraints ----------------------------------

namespace {

class NoJacobianForce : public Force {
 public:
  const char* type() const override { return "no-jacobian"; }
  void apply(const Phase&, Eigen::VectorXd&) const override {}
};

// A bead on a circular wire of radius 1 under gravity, released from the
// horizontal; max relative radius error over 10 s at dt = 0.1.
double beadRadiusError(bool coupled) {
  ParticleSystem system;
  system.addParticle(Vector2d(1.0, 0.0), 1.0);
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
  system.addConstraint(std::make_unique<CircularWireConstraint>(0, Vector2d::Zero(), 1.0));
  ImplicitEulerIntegrator integrator;
  IntegratorSettings settings;
  settings.implicitEuler.coupledConstraints = coupled;
  integrator.configure(settings);
  double worst = 0.0;
  for (int k = 0; k < 100; ++k) {
    system.step(integrator, 0.1);
    if (!system.finite()) return INFINITY;
    worst = std::max(worst, system.maxRelativeConstraintError());
  }
  return worst;
}

}  // namespace

TEST(ImplicitEuler, RefusesAForceWithoutJacobiansNamingIt) {
  ParticleSystem system = oscillator().build();
  system.addForce(std::make_unique<NoJacobianForce>());
  auto integrator = makeIntegrator("implicit-euler");
  try {
    system.step(*integrator, 0.01);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no-jacobian"), std::string::npos) << e.what();
  }
}

TEST(ImplicitEuler, KeepsBeadOnWireWhereLaggedConstraintsDoNot) {
  const double coupled = beadRadiusError(true), lagged = beadRadiusError(false);
  RecordProperty("coupled_radius_error", std::to_string(coupled));
  RecordProperty("lagged_radius_error", std::to_string(lagged));
  EXPECT_LE(coupled, 0.01);
  EXPECT_GT(lagged, 0.01);
}

namespace {

// The report's long test chain: 200 particles, rods of
// 0.1, the first pinned, released horizontally under g = 0.05; 100 s at
// dt = 0.2 (k_s·dt² = 2.4 for the explicit feedback). Returns max |C|/r.
double testChainError(bool coupled) {
  ParticleSystem system;
  const int n = 200;
  for (int i = 0; i < n; ++i) system.addParticle(Vector2d(0.1 * i, 0.0), 1.0);
  system.setPinned(0, true);
  for (int i = 0; i + 1 < n; ++i) system.addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -0.05)));
  ImplicitEulerIntegrator integrator;
  IntegratorSettings settings;
  settings.implicitEuler.coupledConstraints = coupled;
  integrator.configure(settings);
  double worst = 0.0;
  for (int k = 0; k < 500; ++k) {
    system.step(integrator, 0.2);
    if (!system.finite()) return INFINITY;
    worst = std::max(worst, system.maxRelativeConstraintError());
  }
  EXPECT_EQ(system.position(0), Vector2d(0.0, 0.0));  // the pin stays put
  return worst;
}

}  // namespace

TEST(ImplicitEuler, TestChainHoldsItsRodsAtLargeStepWhereLaggedConstraintsDoNot) {
  const double coupled = testChainError(true), lagged = testChainError(false);
  RecordProperty("coupled_max_relative_C", std::to_string(coupled));
  RecordProperty("lagged_max_relative_C", std::to_string(lagged));
  EXPECT_LE(coupled, 0.01);
  EXPECT_GT(lagged, 0.01);
}

TEST(ImplicitEuler, PinnedOnlyConstraintGivesFiniteStep) {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 0.0), 1.0);
  system.addParticle(Vector2d(0.3, 0.0), 1.0);  // violates the rod, both pinned
  system.addParticle(Vector2d(0.0, -0.5), 1.0);
  system.setPinned(0, true);
  system.setPinned(1, true);
  system.addConstraint(std::make_unique<RodConstraint>(0, 1, 0.5));
  system.addConstraint(std::make_unique<RodConstraint>(0, 2, 0.5));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
  auto integrator = makeIntegrator("implicit-euler");
  for (int k = 0; k < 10; ++k) system.step(*integrator, 0.1);
  EXPECT_TRUE(system.finite());
  EXPECT_LT(std::abs((system.position(2) - system.position(0)).norm() - 0.5), 0.005);
}

// An unsatisfiable rod between two pinned particles beside a hanging chain:
// its row is −ν = 0, so it must neither keep the Newton passes going nor move
// the chain. The chain with and without it steps identically.
TEST(ImplicitEuler, NewtonPassesStopOnAPinnedOnlyRowAndLeaveTheRestAlone) {
  auto build = [](bool withPinnedRod) {
    auto s = std::make_unique<ParticleSystem>();
    for (int i = 0; i < 6; ++i) s->addParticle(Vector2d(0.1 * i, 0.0), 1.0);
    s->addParticle(Vector2d(0.0, 1.0), 1.0);
    s->addParticle(Vector2d(0.3, 1.0), 1.0);  // 0.3 apart, the rod wants 0.5
    s->setPinned(0, true);
    s->setPinned(6, true);
    s->setPinned(7, true);
    for (int i = 0; i + 1 < 6; ++i) s->addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
    if (withPinnedRod) s->addConstraint(std::make_unique<RodConstraint>(6, 7, 0.5));
    s->addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
    return s;
  };
  for (double dt : {0.01, 0.05, 0.1}) {
    auto with = build(true), without = build(false);
    ImplicitEulerIntegrator a, b;
    for (int k = 0; k < 100; ++k) {
      const StepStats sa = with->step(a, dt), sb = without->step(b, dt);
      ASSERT_EQ(sa.solves, sb.solves) << "dt " << dt << " step " << k;
      ASSERT_LT(sa.solves, a.settings().constraintPasses) << "dt " << dt << " step " << k;
    }
    const double shift = (with->positions().head(12) - without->positions().head(12)).cwiseAbs().maxCoeff();
    // Only the factorisation's ordering differs (AMD sees one more row): round-off.
    EXPECT_LT(shift, 1e-9) << "dt " << dt;  // in rod lengths: 1e-8
    EXPECT_LE(a.lastConstraintResidual(), a.settings().constraintTolerance) << "dt " << dt;
  }
}

TEST(IntegratorTable, NewSchemesAreListedAndToleranceIsChecked) {
  for (const char* name : {"verlet", "implicit-euler", "dopri5"})
    EXPECT_STREQ(makeIntegrator(name)->name(), name);
  IntegratorSettings bad;
  bad.dopri5.tolerance = -1.0;
  EXPECT_THROW(makeIntegrator("dopri5", bad), std::invalid_argument);
}

TEST(ImplicitEuler, ReusedPatternGivesTheSameStepAsAFreshIntegrator) {
  // The integrator caches the sparsity pattern; after the structure changes
  // (a force added, a particle pinned, a constraint added) its step must equal
  // that of an integrator that never saw the old structure.
  auto build = [] {
    auto s = std::make_unique<ParticleSystem>();
    for (int i = 0; i < 6; ++i) s->addParticle(Vector2d(0.1 * i, 0.02 * (i % 2)), 1.0, Vector2d(0.0, 0.1 * i));
    for (int i = 0; i + 1 < 6; ++i) s->addForce(std::make_unique<SpringForce>(i, i + 1, 0.1, 50.0, 0.3));
    s->addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
    s->setPinned(0, true);
    return s;
  };
  const std::vector<std::function<void(ParticleSystem&)>> changes = {
      [](ParticleSystem& s) { s.addForce(std::make_unique<SpringForce>(1, 4, 0.3, 20.0, 0.1)); },
      [](ParticleSystem& s) { s.setPinned(3, true); },
      [](ParticleSystem& s) { s.addConstraint(std::make_unique<RodConstraint>(2, 5, 0.3)); },
      [](ParticleSystem& s) { s.addForce(std::make_unique<AngularSpringForce>(1, 2, 3, 3.0, 0.5, 0.1)); },
  };
  for (ImplicitLinearSolver solver : {ImplicitLinearSolver::Direct, ImplicitLinearSolver::ConjugateGradient}) {
    auto a = build(), b = build();
    ImplicitEulerIntegrator reused;
    IntegratorSettings settings;
    settings.implicitEuler.solver = solver;
    settings.implicitEuler.cgTolerance = 1e-12;
    // The reused integrator would start its geometric stiffness from the last
    // step's impulses, the fresh one from zero; without it both take the same passes.
    settings.implicitEuler.geometricStiffness = false;
    reused.configure(settings);
    for (std::size_t c = 0; c < changes.size(); ++c) {
      a->step(reused, 0.05);
      b->restore(a->snapshot());
      changes[c](*a);
      changes[c](*b);
      ImplicitEulerIntegrator fresh;
      fresh.configure(settings);
      a->step(reused, 0.05);
      b->step(fresh, 0.05);
      EXPECT_LT((a->positions() - b->positions()).cwiseAbs().maxCoeff(), 1e-10) << "change " << c;
      EXPECT_LT((a->velocities() - b->velocities()).cwiseAbs().maxCoeff(), 1e-10) << "change " << c;
    }
  }
}

// --- backward Euler's energy: it never rises ---------------------------------

namespace {

// The laboratory's long-time scenes (particle-lab longtime), from their seed
// presets: the pendulum (a bead on a wire of radius 0.5 released at 60°,
// g = 0.05) and the 6-chain (test chain, cl = 6, rods of 0.1, unit masses).
// E_s is the energy each can release: m g L (1 − cos 60°) and
// g m L cl (cl − 1)/2 (lab/failure.h).
struct EnergyScene {
  scenes::Scene scene;
  double releasable;
};

EnergyScene pendulumScene() {
  const scenes::PendulumParams p = scenes::PendulumParams::seed();
  return {scenes::buildPendulum(p), p.mass * p.gravity * p.length * (1.0 - std::cos(p.angle * kPi / 180.0))};
}

EnergyScene chainScene() {
  scenes::TestChainParams p = scenes::TestChainParams::seed();
  p.cl = 6;
  return {scenes::buildTestChain(p), p.gravity * p.mass * p.length * p.cl * (p.cl - 1) / 2.0};
}

struct EnergyRecord {
  double worstRise = -INFINITY;  // largest E(t_{k+1}) − E(t_k), in E_s
  double change = 0.0;           // (E(T) − E(0)) / E_s
  int worstPasses = 0;
  double worstResidual = 0.0;     // of the committed steps: max(constraint, momentum) residual
};

EnergyRecord runEnergy(EnergyScene s, double dt, double T) {
  ParticleSystem& system = *s.scene.system;
  ImplicitEulerIntegrator integrator;
  EnergyRecord r;
  const double e0 = system.totalEnergy();
  double last = e0;
  const long steps = std::lround(T / dt);
  for (long k = 0; k < steps; ++k) {
    system.step(integrator, dt);
    const double e = system.totalEnergy();
    r.worstRise = std::max(r.worstRise, (e - last) / s.releasable);
    last = e;
    r.worstPasses = std::max(r.worstPasses, integrator.lastPasses());
    r.worstResidual = std::max({r.worstResidual, integrator.lastConstraintResidual(), integrator.lastMomentumResidual()});
  }
  r.change = (last - e0) / s.releasable;
  return r;
}

// Round-off of E = ½ vᵀM v + Σ m g y on these scenes: a few ulps of the
// largest term (|m g y| ≤ 0.05·0.5 per particle), far below 1e-12 E_s.
constexpr double kRoundOff = 1e-12;

}  // namespace

// Sampled every step: backward Euler loses at least ½|Δv|²_M per step, so the
// energy must fall monotonically up to round-off, at every dt, and visibly so
// at the large ones (the header's identity). Before the discrete-gradient
// impulses and converged passes the 6-chain gained 0.063 E_s over 500 s at
// dt 0.01 (per step up to +2.8e-3 E_s), and the pendulum 0.005 E_s at dt 0.05.
TEST(ImplicitEuler, PendulumEnergyNeverRisesOver200s) {
  for (double dt : {0.005, 0.01, 0.05, 0.1}) {
    const EnergyRecord r = runEnergy(pendulumScene(), dt, 200.0);
    RecordProperty("pendulum_change_dt_" + std::to_string(dt), std::to_string(r.change));
    EXPECT_LE(r.worstRise, kRoundOff) << "dt " << dt;
    EXPECT_LT(r.change, 0.0) << "dt " << dt;
    EXPECT_LE(r.worstResidual, ImplicitEulerSettings{}.constraintTolerance) << "dt " << dt;  // passes converged
    if (dt >= 0.05) {
      EXPECT_LT(r.change, -0.1) << "dt " << dt << ": backward Euler should damp visibly";
    }
  }
}

TEST(ImplicitEuler, ChainEnergyNeverRisesOver500s) {
  for (double dt : {0.005, 0.01, 0.05, 0.1}) {
    const EnergyRecord r = runEnergy(chainScene(), dt, 500.0);
    RecordProperty("chain6_change_dt_" + std::to_string(dt), std::to_string(r.change));
    EXPECT_LE(r.worstRise, kRoundOff) << "dt " << dt;
    EXPECT_LT(r.change, 0.0) << "dt " << dt;
    EXPECT_LE(r.worstResidual, ImplicitEulerSettings{}.constraintTolerance) << "dt " << dt;  // passes converged
    if (dt >= 0.05) {
      EXPECT_LT(r.change, -0.1) << "dt " << dt << ": backward Euler should damp visibly";
    }
  }
}

// The seed's 8-way 10×10 cloth with k_s = 1e5, its top row on a line: hanging
// almost still, f is a sum of large spring terms that cancel, and R₁'s
// round-off floor lies above 1e-10 of |v̄| + h|W f|. Measured against the size
// of those terms (header), every step converges within the tolerance, in a
// few passes rather than running them all out.
TEST(ImplicitEuler, AStiffClothHangingStillConvergesInAFewPasses) {
  scenes::ClothParams params = scenes::ClothParams::seed();
  params.links = 8;
  params.stiffness = 1e5;
  scenes::Scene cloth = scenes::buildCloth(params);
  ParticleSystem& system = *cloth.system;
  ASSERT_GT(system.constraints().size(), 0u) << "the top row is held by constraints, so the passes run";
  ImplicitEulerIntegrator integrator;
  int worstPasses = 0;
  double worstResidual = 0.0;
  for (int k = 0; k < 500; ++k) {
    system.step(integrator, 0.001);
    worstPasses = std::max(worstPasses, integrator.lastPasses());
    worstResidual = std::max({worstResidual, integrator.lastConstraintResidual(), integrator.lastMomentumResidual()});
  }
  EXPECT_LE(worstResidual, integrator.settings().constraintTolerance);
  EXPECT_LE(worstPasses, 4) << "of at most " << integrator.settings().constraintPasses;
}

// Implicit Euler's settings are reached through makeIntegrator, as every other
// scheme's are, and validated there.
TEST(ImplicitEuler, SettingsComeThroughMakeIntegrator) {
  IntegratorSettings settings;
  settings.implicitEuler.constraintPasses = 3;
  settings.implicitEuler.solver = ImplicitLinearSolver::Direct;
  auto made = makeIntegrator("implicit-euler", settings);
  const auto& implicit = dynamic_cast<const ImplicitEulerIntegrator&>(*made);
  EXPECT_EQ(implicit.settings().constraintPasses, 3);
  EXPECT_EQ(implicit.settings().solver, ImplicitLinearSolver::Direct);
  settings.implicitEuler.stabilization = 2.0;
  try {
    makeIntegrator("implicit-euler", settings);
    FAIL() << "an implicit stabilization of 2 was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("stabilization"), std::string::npos) << e.what();
  }
}

// The constraint solve: the matrix-free CG λ against a dense solve of
//   (J W Jᵀ) λ = −J̇ q̇ − J W Q − k_s C − k_d Ċ,
// the resulting accelerations against J q̈ + J̇ q̇ = −k_s C − k_d Ċ, and the
// singular systems that must stay finite.
#include <cmath>
#include <random>

#include <Eigen/Dense>
#include <gtest/gtest.h>


#include "particles/constraints/circular_wire.h"
#include "particles/constraints/line.h"
#include "particles/constraints/rod.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "integrators/rk4.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"
#include "test_support.h"

using namespace particles;
using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::VectorXd;
using test_support::expectRejected;

namespace {

// Every solve method, and every combination of preconditioner and warm start
// for conjugate gradient.
struct Variant {
  SolveMethod method;
  Preconditioner preconditioner;
  bool warmStart;
};
const Variant kVariants[] = {{SolveMethod::ConjugateGradient, Preconditioner::Jacobi, true},
                             {SolveMethod::ConjugateGradient, Preconditioner::Jacobi, false},
                             {SolveMethod::ConjugateGradient, Preconditioner::None, true},
                             {SolveMethod::ConjugateGradient, Preconditioner::None, false},
                             {SolveMethod::ConjugateGradient, Preconditioner::IncompleteCholesky, true},
                             {SolveMethod::Direct, Preconditioner::None, false}};

// A pinned particle with a chain of three rods (squared, root, squared) below
// it, a bead on a circular wire, a bead on a line, a spring and gravity.
ParticleSystem makeMixedSystem() {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 0.0), 1.0);
  system.addParticle(Vector2d(0.3, 0.0), 0.7);
  system.addParticle(Vector2d(0.6, -0.1), 1.3);
  system.addParticle(Vector2d(0.8, -0.3), 0.9);
  system.addParticle(Vector2d(1.3, 0.0), 1.1);
  system.addParticle(Vector2d(-0.5, 0.2), 0.6);
  system.setPinned(0, true);
  system.addConstraint(std::make_unique<RodConstraint>(0, 1, 0.3, RodForm::Squared));
  system.addConstraint(std::make_unique<RodConstraint>(1, 2, 0.3, RodForm::Root));
  system.addConstraint(std::make_unique<RodConstraint>(2, 3, 0.3, RodForm::Squared));
  system.addConstraint(std::make_unique<CircularWireConstraint>(4, Vector2d(1.0, 0.0), 0.3));
  system.addConstraint(std::make_unique<LineConstraint>(5, Vector2d(0.0, 0.2), 0.4));
  system.addForce(std::make_unique<SpringForce>(3, 4, 0.4, 5.0, 0.5));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  return system;
}

// Moves every movable particle a little and gives it a random velocity, so
// that C, Ċ and J̇ q̇ are all non-zero.
void perturb(ParticleSystem& system, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < system.size(); ++i) {
    if (system.pinned(i)) continue;
    system.setPosition(i, system.position(i) + 0.02 * Vector2d(u(rng), u(rng)));
    system.setVelocity(i, Vector2d(u(rng), u(rng)));
  }
}

// The pieces of the constraint system at the current state, gathered without
// the solver: Q from the force objects, C and Ċ from the constraint objects.
struct ConstraintTerms {
  VectorXd Q, C, Cdot;
  MatrixXd J, Jdot;  // m × 2n, from the constraint objects' own rows
  MatrixXd W;        // 2n × 2n diagonal of inverse masses
};

ConstraintTerms gatherIndependently(const ParticleSystem& system) {
  const Phase s = system.phase();
  ConstraintTerms t;
  t.Q = VectorXd::Zero(2 * system.size());
  for (const auto& force : system.forceObjects()) force->apply(s, t.Q);
  const int m = static_cast<int>(system.constraints().size());
  t.C.resize(m);
  t.Cdot.resize(m);
  t.J = t.Jdot = MatrixXd::Zero(m, 2 * system.size());
  for (int k = 0; k < m; ++k) {
    const Constraint& c = *system.constraints()[k];
    std::vector<Vector2d> J(c.particles().size()), Jdot(J.size());
    ConstraintRow row;
    row.J = J.data();
    row.Jdot = Jdot.data();
    c.evaluate(s, row);
    t.C[k] = row.C;
    t.Cdot[k] = row.Cdot;
    for (std::size_t e = 0; e < J.size(); ++e) {
      t.J.block<1, 2>(k, 2 * c.particles()[e]) += J[e].transpose();
      t.Jdot.block<1, 2>(k, 2 * c.particles()[e]) += Jdot[e].transpose();
    }
  }
  VectorXd w(2 * system.size());
  for (int i = 0; i < system.size(); ++i) w.segment<2>(2 * i).setConstant(system.inverseMasses()[i]);
  t.W = w.asDiagonal();
  return t;
}

// Evaluates q̈ at the system's state and checks λ against a dense solve and
// q̈ against the constraint's second derivative, J q̈ + J̇ q̇ = −k_s C − k_d Ċ.
void expectSolveMatchesDenseSystem(ParticleSystem& system) {
  VectorXd a;
  system.acceleration(system.positions(), system.velocities(), a);
  const ConstraintSolver& solver = system.solver();
  const SolverSettings& settings = solver.settings;
  const int n = system.size();
  const MatrixXd J = solver.denseJ(n), Jdot = solver.denseJdot(n);
  const ConstraintTerms t = gatherIndependently(system);
  const VectorXd& v = system.velocities();
  EXPECT_EQ(J, t.J) << "the solver gathered rows other than the constraints'";
  EXPECT_EQ(Jdot, t.Jdot);

  const VectorXd b = -Jdot * v - J * t.W * t.Q - settings.stiffness * t.C - settings.damping * t.Cdot;
  const MatrixXd A = J * t.W * J.transpose();
  const VectorXd lambda = A.ldlt().solve(b);
  ASSERT_EQ(solver.lambda().size(), lambda.size());
  EXPECT_LT((solver.lambda() - lambda).norm(), 1e-6 * lambda.norm())
      << "CG λ = " << solver.lambda().transpose() << "\ndense λ = " << lambda.transpose();
  EXPECT_LE((A * solver.lambda() - b).norm(), 1.01 * settings.tolerance * b.norm());
  EXPECT_LE(solver.stats().residual, settings.tolerance);
  EXPECT_EQ(solver.stats().constraints, 5);

  const VectorXd secondDerivative = J * a + Jdot * v;
  const VectorXd target = -settings.stiffness * t.C - settings.damping * t.Cdot;
  EXPECT_LT((secondDerivative - target).norm(), 1e-6 * (1.0 + target.norm()))
      << "J q̈ + J̇ q̇ = " << secondDerivative.transpose() << "\n−k_s C − k_d Ċ = " << target.transpose();
}

}  // namespace

TEST(ConstraintSolver, ConjugateGradientMatchesDenseSolve) {
  for (const Variant& variant : kVariants) {
    SCOPED_TRACE(testing::Message() << "direct " << (variant.method == SolveMethod::Direct) << ", preconditioner "
                                    << static_cast<int>(variant.preconditioner)
                                    << ", warm start " << variant.warmStart);
    std::mt19937 rng(7);
    ParticleSystem system = makeMixedSystem();
    system.solver().settings.method = variant.method;
    system.solver().settings.preconditioner = variant.preconditioner;
    system.solver().settings.warmStart = variant.warmStart;
    system.solver().settings.tolerance = 1e-10;
    // Several solves in a row, so that a warm start begins from the last λ.
    for (int trial = 0; trial < 5; ++trial) {
      perturb(system, rng);
      expectSolveMatchesDenseSystem(system);
    }
  }
}

TEST(ConstraintSolver, FeedbackGainsEnterTheRightHandSide) {
  std::mt19937 rng(8);
  ParticleSystem system = makeMixedSystem();
  system.solver().settings.stiffness = 250.0;
  system.solver().settings.damping = 3.0;
  system.solver().settings.tolerance = 1e-10;
  perturb(system, rng);
  expectSolveMatchesDenseSystem(system);
}

TEST(ConstraintSolver, WarmStartAtTheSameStateNeedsNoFurtherIterations) {
  std::mt19937 rng(9);
  for (bool warm : {true, false}) {
    ParticleSystem system = makeMixedSystem();
    system.solver().settings.method = SolveMethod::ConjugateGradient;  // the direct default has no iterations
    system.solver().settings.warmStart = warm;
    perturb(system, rng);
    VectorXd a;
    system.acceleration(system.positions(), system.velocities(), a);
    const int first = system.lastSolve().iterations;
    system.acceleration(system.positions(), system.velocities(), a);
    const int second = system.lastSolve().iterations;
    EXPECT_GT(first, 0);
    if (warm)
      EXPECT_EQ(second, 0) << "λ from the first solve already solves the second";
    else
      EXPECT_EQ(second, first) << "a cold start repeats the same iterations";
  }
}

TEST(ConstraintSolver, SystemWithoutConstraintsDoesNoSolve) {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 1.0), 2.0);
  system.addParticle(Vector2d(0.5, 1.0), 1.0);
  system.addForce(std::make_unique<SpringForce>(0, 1, 0.3, 4.0, 0.0));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  VectorXd a;
  system.acceleration(system.positions(), system.velocities(), a);
  EXPECT_EQ(system.lastSolve().constraints, 0);
  EXPECT_EQ(system.lastSolve().iterations, 0);
  EXPECT_EQ(system.solver().lambda().size(), 0);
  EXPECT_EQ(system.solver().rhs().size(), 0);
  // Without a solve, q̈ is W Q exactly: spring force 0.8 along −x on particle 0.
  EXPECT_NEAR(a[0], 0.8 / 2.0, 1e-15);
  EXPECT_NEAR(a[1], -9.81, 1e-15);
  EXPECT_NEAR(a[2], -0.8, 1e-15);
}

// A rod between two pinned particles has an all-zero row in W Jᵀ, so J W Jᵀ
// is singular; its λ must be 0 and the rest of the system must solve normally.
TEST(ConstraintSolver, ConstraintOnPinnedParticlesOnlyGivesFiniteResult) {
  for (const Variant& variant : kVariants) {
    ParticleSystem system;
    system.addParticle(Vector2d(0.0, 0.0), 1.0);
    system.addParticle(Vector2d(0.5, 0.0), 1.0);  // rod of 0.4: violated, and cannot be fixed
    system.addParticle(Vector2d(0.5, -0.3), 1.0);
    system.setPinned(0, true);
    system.setPinned(1, true);
    system.addConstraint(std::make_unique<RodConstraint>(0, 1, 0.4));
    system.addConstraint(std::make_unique<RodConstraint>(1, 2, 0.3));
    system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
    system.setVelocity(2, Vector2d(1.0, 0.0));
    system.solver().settings.method = variant.method;
    system.solver().settings.preconditioner = variant.preconditioner;
    system.solver().settings.warmStart = variant.warmStart;
    VectorXd a;
    system.acceleration(system.positions(), system.velocities(), a);
    ASSERT_TRUE(a.allFinite());
    ASSERT_TRUE(system.solver().lambda().allFinite());
    EXPECT_EQ(system.solver().lambda()[0], 0.0);
    EXPECT_EQ(a.head<4>(), Eigen::Vector4d::Zero());
    // The pendulum row still holds: with C = 0 (squared form), J q̈ + J̇ q̇ = −k_d Ċ = 0
    // means the centripetal acceleration |v|²/r points up, at the pivot.
    EXPECT_NEAR(a[4], 0.0, 1e-9);
    EXPECT_NEAR(a[5], 1.0 / 0.3, 1e-9);
  }
}

TEST(ConstraintSolver, OnlyPinnedConstraintsDoNoIterations) {
  ParticleSystem system;
  system.addParticle(Vector2d(0.0, 0.0), 1.0);
  system.addParticle(Vector2d(0.5, 0.0), 1.0);
  system.addParticle(Vector2d(2.0, 0.0), 1.0);
  system.setPinned(0, true);
  system.setPinned(1, true);
  system.addConstraint(std::make_unique<RodConstraint>(0, 1, 0.4));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  VectorXd a;
  system.acceleration(system.positions(), system.velocities(), a);
  EXPECT_EQ(system.lastSolve().constraints, 1);
  EXPECT_EQ(system.lastSolve().iterations, 0);
  EXPECT_EQ(system.solver().lambda()[0], 0.0);
  EXPECT_EQ(a[5], -9.81);
}

// The seed report's explosion case: a fully straight chain of rods whose two
// ends ride on circular wires centred on the chain's line. Every row of J is
// along the line, so J W Jᵀ ((links + 2) rows, links + 1 independent columns)
// loses rank, and once the chain moves b has a part outside its range.
namespace {
ParticleSystem makeStraightChainBetweenWires(RodForm form) {
  const int links = 10;
  const double rod = 0.1, wireRadius = 0.3, length = links * rod;
  ParticleSystem system;
  for (int i = 0; i <= links; ++i) system.addParticle(Vector2d(i * rod, 0.0), 1.0);
  for (int i = 0; i < links; ++i)
    system.addConstraint(std::make_unique<RodConstraint>(i, i + 1, rod, form));
  system.addConstraint(std::make_unique<CircularWireConstraint>(0, Vector2d(-wireRadius, 0.0), wireRadius));
  system.addConstraint(
      std::make_unique<CircularWireConstraint>(links, Vector2d(length + wireRadius, 0.0), wireRadius));
  system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
  return system;
}
}  // namespace

TEST(ConstraintSolver, StraightChainBetweenTwoWiresGivesFiniteSolve) {
  for (const Variant& variant : kVariants) {
    SCOPED_TRACE(testing::Message() << "direct " << (variant.method == SolveMethod::Direct) << ", preconditioner "
                                    << static_cast<int>(variant.preconditioner)
                                    << ", warm start " << variant.warmStart);
    for (RodForm form : {RodForm::Squared, RodForm::Root}) {
      ParticleSystem system = makeStraightChainBetweenWires(form);
      system.solver().settings.method = variant.method;
      system.solver().settings.preconditioner = variant.preconditioner;
      system.solver().settings.warmStart = variant.warmStart;
      // Falling particles make b inconsistent: the wires ask the two ends for
      // opposite centripetal accelerations along the line, the rods for equal ones.
      std::mt19937 rng(5);
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      for (int i = 0; i < system.size(); ++i) system.setVelocity(i, Vector2d(system.velocity(i).x(), -0.5 + 0.1 * u(rng)));

      VectorXd a;
      for (int solve = 0; solve < 3; ++solve) {  // a repeated solve starts warm from the first
        system.acceleration(system.positions(), system.velocities(), a);
        const MatrixXd J = system.solver().denseJ(system.size());
        Eigen::FullPivLU<MatrixXd> lu(J * J.transpose());
        lu.setThreshold(1e-10);
        ASSERT_LT(lu.rank(), system.solver().stats().constraints) << "J W Jᵀ has full rank";
        EXPECT_TRUE(a.allFinite());
        EXPECT_TRUE(system.solver().lambda().allFinite());
        EXPECT_TRUE(std::isfinite(system.solver().stats().residual));
      }
    }
  }
}

// The two wires touch the chain's ends at the only points where it fits, so
// the configuration is locked, and a straight chain can hold a transverse load
// only with unbounded tension: J W Jᵀ loses rank. An explicit scheme asks the
// solve for the consistent λ (about 4e5 after the first RK4 step at g = 9.81)
// and is thrown off the wires within a few steps; that explosion is measured
// by `particle-lab extremes`. Implicit Euler solves the constraints inside its
// step as a saddle-point system with a tiny compliance, which bounds the
// multipliers: the chain stays on its wires, close to its length.
TEST(ConstraintSolver, StraightChainBetweenTwoWiresStaysBoundedUnderImplicitEuler) {
  for (RodForm form : {RodForm::Squared, RodForm::Root}) {
    ParticleSystem system = makeStraightChainBetweenWires(form);
    auto implicit = makeIntegrator("implicit-euler");
    for (int step = 0; step < 300; ++step) {
      system.step(*implicit, 0.01);
      ASSERT_TRUE(system.finite()) << "step " << step;
      ASSERT_LT(system.positions().cwiseAbs().maxCoeff(), 10.0) << "step " << step;
    }
    EXPECT_LT(system.maxRelativeConstraintError(), 0.05) << system.maxRelativeConstraintError();
    EXPECT_GT(system.time(), 2.99);
  }
}

TEST(SolverSettings, RejectedWithTheirName) {
  auto with = [](auto change) {
    return [change] {
      SolverSettings s;
      change(s);
      s.validate();
    };
  };
  const double nan = std::nan("");
  SolverSettings defaults;
  EXPECT_NO_THROW(defaults.validate());
  expectRejected(with([](SolverSettings& s) { s.tolerance = 0.0; }), "solver tolerance");
  expectRejected(with([](SolverSettings& s) { s.tolerance = -1e-8; }), "solver tolerance");
  expectRejected(with([&](SolverSettings& s) { s.tolerance = nan; }), "solver tolerance");
  expectRejected(with([](SolverSettings& s) { s.maxIterations = -1; }), "solver max iterations");
  expectRejected(with([](SolverSettings& s) { s.stiffness = -60.0; }), "stiffness");
  expectRejected(with([&](SolverSettings& s) { s.stiffness = nan; }), "stiffness");
  expectRejected(with([](SolverSettings& s) { s.damping = -10.0; }), "damping");
  expectRejected(with([&](SolverSettings& s) { s.damping = nan; }), "damping");
}

// Rank loss with inconsistency: a bead on a circular wire and on the line
// tangent to it at the bottom. J W Jᵀ is singular there (both normals
// vertical), and once the bead moves along the line the two constraints agree
// only at the tangent point. Every integrator must keep it finite, with a
// bounded constraint error, for 5 s.
TEST(ConstraintSolver, BeadOnAWireAndItsTangentLineStaysFiniteUnderEveryIntegrator) {
  for (const IntegratorInfo& info : integratorTable()) {
    ParticleSystem system;
    system.addParticle(Vector2d(0.0, -0.5), 1.0, Vector2d(1e-3, 0.0));
    system.addConstraint(std::make_unique<CircularWireConstraint>(0, Vector2d(0.0, 0.0), 0.5));
    system.addConstraint(std::make_unique<LineConstraint>(0, Vector2d(0.0, -0.5), 0.0));
    system.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.81)));
    auto integrator = makeIntegrator(info.name);
    double worst = 0.0;
    bool finite = true;
    for (int step = 0; step < 500 && finite; ++step) {
      const StepStats stats = system.step(*integrator, 0.01);
      finite = system.finite() && stats.failure == StepFailure::None;
      worst = std::max(worst, system.maxConstraintError());
    }
    EXPECT_TRUE(finite) << info.name << " at t = " << system.time();
    EXPECT_LT(worst, 1e-2) << info.name;
    RecordProperty(std::string("max_C_") + info.name, std::to_string(worst));
  }
}

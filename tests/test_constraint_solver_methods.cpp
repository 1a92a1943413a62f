// The constraint solve by each method — plain and Jacobi
// matrix-free CG with and without warm start, incomplete-Cholesky CG, and the
// sparse direct LDLᵀ — against a dense solve of the same J W Jᵀ λ = b.
#include <random>
#include <string>
#include <type_traits>

#include <Eigen/Dense>
#include <gtest/gtest.h>


#include "particles/constraints/circular_wire.h"
#include "particles/constraints/line.h"
#include "particles/constraints/rod.h"
#include "particles/forces/gravity.h"
#include "particles/forces/spring.h"
#include "particles/integrator.h"
#include "particles/particle_system.h"

using namespace particles;
using Eigen::Vector2d;

// The factorisations the solver keeps must not stop a ParticleSystem from
// being returned by value (scene builders and tests do).
static_assert(std::is_move_constructible<ParticleSystem>::value, "ParticleSystem must stay movable");

namespace {

struct Method {
  const char* name;
  SolveMethod method;
  Preconditioner preconditioner;
  bool warmStart;
};

const Method kMethods[] = {
    {"plain CG", SolveMethod::ConjugateGradient, Preconditioner::None, false},
    {"Jacobi CG, warm", SolveMethod::ConjugateGradient, Preconditioner::Jacobi, true},
    {"IC-CG, warm", SolveMethod::ConjugateGradient, Preconditioner::IncompleteCholesky, true},
    {"direct LDLT", SolveMethod::Direct, Preconditioner::Jacobi, true},
};

// A grid of particles joined by rods along every row and down two columns
// (closed loops, so J W Jᵀ is not banded, yet fewer constraints than degrees
// of freedom: full rank), a circular wire and a line on two of them, jittered
// off the constraints, with random velocities; particle 0 pinned.
std::unique_ptr<ParticleSystem> rodMesh(std::mt19937& rng, RodForm form) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto s = std::make_unique<ParticleSystem>();
  const int w = 6, h = 5;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      s->addParticle(Vector2d(0.1 * c + 0.01 * u(rng), -0.1 * r + 0.01 * u(rng)), 1.0 + 0.5 * (u(rng) + 1),
                     Vector2d(u(rng), u(rng)));
  auto id = [&](int r, int c) { return r * w + c; };
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      if (c + 1 < w) s->addConstraint(std::make_unique<RodConstraint>(id(r, c), id(r, c + 1), 0.1, form));
      if (r + 1 < h && (c == 0 || c == 3))
        s->addConstraint(std::make_unique<RodConstraint>(id(r, c), id(r + 1, c), 0.1, form));
    }
  s->addConstraint(std::make_unique<CircularWireConstraint>(id(0, w - 1), Vector2d(0.5, 0.3), 0.3));
  s->addConstraint(std::make_unique<LineConstraint>(id(h - 1, 0), Vector2d(0.0, -0.4), 0.2));
  s->setPinned(0, true);
  s->addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
  s->addForce(std::make_unique<SpringForce>(id(1, 1), id(3, 4), 0.2, 5.0, 0.5));
  return s;
}

// λ of a dense solve of the system the solver just set up (rows whose
// diagonal is zero — every particle pinned — have λ = 0).
Eigen::VectorXd denseLambda(const ParticleSystem& s) {
  const ConstraintSolver& solver = s.solver();
  const Eigen::MatrixXd J = solver.denseJ(s.size());
  Eigen::VectorXd w2(2 * s.size());
  for (int i = 0; i < s.size(); ++i) w2.segment<2>(2 * i).setConstant(s.inverseMasses()[i]);
  Eigen::MatrixXd A = J * w2.asDiagonal() * J.transpose();
  Eigen::VectorXd b = solver.rhs();
  for (int k = 0; k < A.rows(); ++k)
    if (A(k, k) == 0.0) A(k, k) = 1.0, b[k] = 0.0;
  return A.ldlt().solve(b);
}

void expectSameLambdaAsDense(RodForm form) {
  for (const Method& method : kMethods) {
    std::mt19937 rng(11);
    auto s = rodMesh(rng, form);
    SolverSettings& settings = s->solver().settings;
    settings.method = method.method;
    settings.preconditioner = method.preconditioner;
    settings.warmStart = method.warmStart;
    settings.tolerance = 1e-12;
    Eigen::VectorXd a;
    // Several evaluations along a trajectory so that warm starts are used.
    for (int step = 0; step < 3; ++step) {
      s->setPositions(s->positions() + 0.002 * s->velocities());
      s->acceleration(s->positions(), s->velocities(), a);
      const Eigen::VectorXd expected = denseLambda(*s);
      const Eigen::VectorXd& lambda = s->solver().lambda();
      ASSERT_EQ(lambda.size(), expected.size());
      EXPECT_LT((lambda - expected).norm(), 1e-7 * expected.norm())
          << method.name << ", step " << step << ", " << rodFormName(form) << " rods";
    }
    if (method.method == SolveMethod::ConjugateGradient) {
      EXPECT_GT(s->lastSolve().iterations, 0) << method.name;
    } else {
      EXPECT_EQ(s->lastSolve().iterations, 0) << method.name;  // no CG fallback here
    }
  }
}

}  // namespace

TEST(ConstraintSolverMethods, EveryMethodMatchesDenseSolveSquaredRods) {
  expectSameLambdaAsDense(RodForm::Squared);
}

TEST(ConstraintSolverMethods, EveryMethodMatchesDenseSolveRootRods) {
  expectSameLambdaAsDense(RodForm::Root);
}

TEST(ConstraintSolverMethods, IncompleteCholeskyIsExactOnAChain) {
  // J W Jᵀ of a chain is tridiagonal: IC has no fill to drop, so CG converges at once.
  ParticleSystem s;
  for (int i = 0; i < 80; ++i) s.addParticle(Vector2d(0.1 * i, 0.01 * (i % 3)), 1.0);
  s.setPinned(0, true);
  for (int i = 0; i + 1 < 80; ++i) s.addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
  s.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -0.05)));
  s.solver().settings.method = SolveMethod::ConjugateGradient;
  s.solver().settings.preconditioner = Preconditioner::IncompleteCholesky;
  s.solver().settings.warmStart = false;
  Eigen::VectorXd a;
  s.acceleration(s.positions(), s.velocities(), a);
  EXPECT_LE(s.lastSolve().iterations, 2);
  EXPECT_LT(s.lastSolve().residual, 1e-8);
}

// A chain of rods in the list's order (J W Jᵀ tridiagonal: the direct solve's
// O(m) path), bent, with random masses and velocities and its first rod's
// both ends pinned (a dead row): the direct solve's λ is the dense solve's,
// along a trajectory. The same chain with one rod more, from its middle to
// its end, is no chain: the sparse path, the same answer.
TEST(ConstraintSolverMethods, AChainsDirectSolveMatchesTheDenseSolve) {
  for (const bool closed : {false, true}) {
    SCOPED_TRACE(closed ? "one rod more: not a chain" : "a chain");
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    ParticleSystem s;
    const int n = 40;
    for (int i = 0; i < n; ++i)
      s.addParticle(Vector2d(0.1 * i, 0.03 * u(rng)), 1.0 + 0.5 * (u(rng) + 1.0), Vector2d(u(rng), u(rng)));
    s.setPinned(0, true);
    s.setPinned(1, true);
    for (int i = 0; i + 1 < n; ++i) s.addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
    if (closed) s.addConstraint(std::make_unique<RodConstraint>(n / 2, n - 1, 1.9));
    s.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
    s.solver().settings.method = SolveMethod::Direct;
    Eigen::VectorXd a;
    for (int step = 0; step < 3; ++step) {
      s.setPositions(s.positions() + 0.002 * s.velocities());
      s.acceleration(s.positions(), s.velocities(), a);
      const Eigen::VectorXd expected = denseLambda(s);
      // From the second evaluation the chain's rods form it in their own pass
      // (rod_chain.h), the dead first row then assembled and factorised again.
      EXPECT_EQ(s.solver().stats().chainPass, !closed && step > 0);
      EXPECT_EQ(s.solver().lambda()[0], 0.0);
      EXPECT_LT((s.solver().lambda() - expected).norm(), 1e-9 * expected.norm()) << "step " << step;
      EXPECT_LT(s.lastSolve().residual, 1e-12);
      EXPECT_FALSE(s.lastSolve().regularized);
    }
  }
}

// A chain of rods of both forms, one of them named end first, its first
// particle pinned, under gravity and a spring: from the second evaluation on
// the direct solve forms the rows, b and J W Jᵀ by the rods' own pass
// (constraints/rod_chain.h). Along a trajectory its rows, b, λ and
// accelerations are those of the generic gather (a fresh system at the same
// state, whose first evaluation gathers), and λ is the dense solve's.
TEST(ConstraintSolverMethods, AChainOfRodsOwnPassMatchesTheGather) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 24;
  std::vector<Vector2d> x, v;
  std::vector<double> mass;
  for (int i = 0; i < n; ++i) {
    x.emplace_back(0.1 * i, 0.03 * u(rng));
    v.emplace_back(u(rng), u(rng));
    mass.push_back(1.0 + 0.5 * (u(rng) + 1.0));
  }
  auto make = [&] {
    auto s = std::make_unique<ParticleSystem>();
    for (int i = 0; i < n; ++i) s->addParticle(x[i], mass[i], v[i]);
    s->setPinned(0, true);
    for (int i = 0; i + 1 < n; ++i) {
      const RodForm form = i % 3 == 1 ? RodForm::Root : RodForm::Squared;
      if (i == 7) s->addConstraint(std::make_unique<RodConstraint>(i + 1, i, 0.1, form));
      else s->addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1, form));
    }
    s->addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
    s->addForce(std::make_unique<SpringForce>(3, 17, 1.0, 5.0, 0.5));
    s->solver().settings.method = SolveMethod::Direct;
    return s;
  };
  auto chain = make();
  Eigen::VectorXd a, expectedA;
  for (int step = 0; step < 4; ++step) {
    SCOPED_TRACE("evaluation " + std::to_string(step));
    chain->setPositions(chain->positions() + 0.002 * chain->velocities());
    chain->acceleration(chain->positions(), chain->velocities(), a);
    EXPECT_EQ(chain->solver().stats().chainPass, step > 0);
    auto gathered = make();
    gathered->setPositions(chain->positions());
    gathered->setVelocities(chain->velocities());
    gathered->acceleration(gathered->positions(), gathered->velocities(), expectedA);
    ASSERT_FALSE(gathered->solver().stats().chainPass);
    const ConstraintSolver &own = chain->solver(), &generic = gathered->solver();
    EXPECT_EQ(own.denseJ(n), generic.denseJ(n));
    EXPECT_EQ(own.denseJdot(n), generic.denseJdot(n));
    EXPECT_LE((own.rhs() - generic.rhs()).norm(), 1e-14 * generic.rhs().norm());
    EXPECT_LE((own.lambda() - generic.lambda()).norm(), 1e-12 * generic.lambda().norm());
    EXPECT_LE((a - expectedA).norm(), 1e-12 * expectedA.norm());
    EXPECT_LT((own.lambda() - denseLambda(*chain)).norm(), 1e-9 * own.lambda().norm());
    EXPECT_FALSE(chain->lastSolve().regularized);
    EXPECT_LT(chain->lastSolve().residual, 1e-12);
  }
}

// A straight chain pinned at both ends, fully extended: its rods pull only
// along the line, and there are more of them than free coordinates along it,
// so J W Jᵀ (tridiagonal) loses rank. The chain's direct solve notices the
// lost pivot and damps the solve as the sparse one does: |λ| ≤ |b|/μ. The
// second evaluation factorises in the rods' own pass first (rod_chain.h).
TEST(ConstraintSolverMethods, ATautChainsDirectSolveIsDamped) {
  ParticleSystem s;
  const int n = 8;
  for (int i = 0; i < n; ++i) s.addParticle(Vector2d(0.1 * i, 0.0), 1.0, Vector2d(0.0, i % 2 ? 0.3 : -0.2));
  s.setPinned(0, true);
  s.setPinned(n - 1, true);
  for (int i = 0; i + 1 < n; ++i) s.addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
  s.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
  s.solver().settings.method = SolveMethod::Direct;
  Eigen::VectorXd a;
  for (int evaluation = 0; evaluation < 2; ++evaluation) {
    s.acceleration(s.positions(), s.velocities(), a);
    EXPECT_EQ(s.solver().stats().chainPass, evaluation > 0);
    EXPECT_TRUE(a.allFinite());
    EXPECT_TRUE(s.lastSolve().regularized);
    EXPECT_EQ(s.lastSolve().factorizations, 2);
    const Eigen::MatrixXd J = s.solver().denseJ(n);
    const double diagMax = (J * J.transpose()).diagonal().maxCoeff();  // unit masses: W = I
    EXPECT_LE(s.solver().lambda().norm(), s.solver().rhs().norm() / (1e-6 * diagMax) * (1.0 + 1e-9));
  }
}

TEST(ConstraintSolverMethods, PinnedOnlyRowsGetZeroLambdaInEveryMethod) {
  for (const Method& method : kMethods) {
    ParticleSystem s;
    s.addParticle(Vector2d(0.0, 0.0), 1.0);
    s.addParticle(Vector2d(0.3, 0.0), 1.0);
    s.addParticle(Vector2d(0.0, -0.5), 1.0);
    s.setPinned(0, true);
    s.setPinned(1, true);
    s.addConstraint(std::make_unique<RodConstraint>(0, 1, 0.5));  // violated, both ends pinned
    s.addConstraint(std::make_unique<RodConstraint>(0, 2, 0.5));
    s.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
    s.solver().settings.method = method.method;
    s.solver().settings.preconditioner = method.preconditioner;
    Eigen::VectorXd a;
    s.acceleration(s.positions(), s.velocities(), a);
    ASSERT_TRUE(a.allFinite()) << method.name;
    EXPECT_EQ(s.solver().lambda()[0], 0.0) << method.name;
    EXPECT_NEAR(a[5], 0.0, 1e-9) << method.name;  // the rod holds particle 2 up
  }
}

TEST(ConstraintSolverMethods, TautChainBetweenWiresStaysFiniteInEveryMethod) {
  // A straight chain whose ends ride on circular wires, fully extended: J W Jᵀ
  // loses rank. The direct solve must notice and not return a huge λ.
  for (const Method& method : kMethods) {
    ParticleSystem s;
    const int n = 6;
    for (int i = 0; i < n; ++i) s.addParticle(Vector2d(0.1 * i, 0.0), 1.0, Vector2d(0.0, i % 2 ? 0.3 : -0.2));
    for (int i = 0; i + 1 < n; ++i) s.addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
    s.addConstraint(std::make_unique<CircularWireConstraint>(0, Vector2d(-0.2, 0.0), 0.2));
    s.addConstraint(std::make_unique<CircularWireConstraint>(n - 1, Vector2d(0.7, 0.0), 0.2));
    s.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
    s.solver().settings.method = method.method;
    s.solver().settings.preconditioner = method.preconditioner;
    Eigen::VectorXd a;
    s.acceleration(s.positions(), s.velocities(), a);
    EXPECT_TRUE(a.allFinite()) << method.name;
    EXPECT_TRUE(s.solver().lambda().allFinite()) << method.name;
    // b has a part outside the range of J W Jᵀ here, so no λ solves the
    // system; the direct solve detects the lost pivot and damps the solve,
    // (J W Jᵀ + μ I) λ = b with μ = 1e-6·max diag, so |λ| ≤ |b|/μ.
    if (method.method == SolveMethod::Direct) {
      EXPECT_TRUE(s.lastSolve().regularized);
      const Eigen::MatrixXd J = s.solver().denseJ(n);
      const double diagMax = (J * J.transpose()).diagonal().maxCoeff();  // unit masses: W = I
      EXPECT_LE(s.solver().lambda().norm(), s.solver().rhs().norm() / (1e-6 * diagMax) * (1.0 + 1e-9));
    }
  }
}

TEST(ConstraintSolverMethods, AddedConstraintRebuildsTheAssembledPattern) {
  for (const Method& method : kMethods) {
    ParticleSystem s;
    for (int i = 0; i < 10; ++i) s.addParticle(Vector2d(0.1 * i, 0.02 * (i % 2)), 1.0, Vector2d(0.0, 0.1 * i));
    s.setPinned(0, true);
    for (int i = 0; i + 1 < 10; ++i) s.addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
    s.addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
    s.solver().settings.method = method.method;
    s.solver().settings.preconditioner = method.preconditioner;
    s.solver().settings.tolerance = 1e-12;
    Eigen::VectorXd a;
    s.acceleration(s.positions(), s.velocities(), a);
    s.addConstraint(std::make_unique<RodConstraint>(2, 7, 0.45));  // couples rows far apart
    s.acceleration(s.positions(), s.velocities(), a);
    const Eigen::VectorXd expected = denseLambda(s);
    EXPECT_LT((s.solver().lambda() - expected).norm(), 1e-7 * expected.norm()) << method.name;
  }
}

namespace {

// A hanging 200-rod chain, bent, under CG without warm start, with a given work bound.
std::unique_ptr<ParticleSystem> bentChain(double maxCgWork) {
  auto s = std::make_unique<ParticleSystem>();
  const int n = 201;
  for (int i = 0; i < n; ++i)
    s->addParticle(Vector2d(0.1 * i, 0.03 * (i % 4)), 1.0, Vector2d(0.0, 0.01 * (i % 7)));
  s->setPinned(0, true);
  for (int i = 0; i + 1 < n; ++i) s->addConstraint(std::make_unique<RodConstraint>(i, i + 1, 0.1));
  s->addForce(std::make_unique<GravityForce>(Vector2d(0.0, -9.8)));
  SolverSettings& settings = s->solver().settings;
  settings.method = SolveMethod::ConjugateGradient;
  settings.preconditioner = Preconditioner::None;
  settings.warmStart = false;
  settings.tolerance = 1e-12;
  settings.maxCgWork = maxCgWork;
  return s;
}

}  // namespace

TEST(ConstraintSolverMethods, CgPastItsWorkBoundFallsBackToTheDirectSolve) {
  // 200 rods: J has 400 entries, an iteration 800 products; a bound of 8,000
  // allows 10 iterations, far from converged on a chain.
  auto reference = bentChain(0.0);
  reference->solver().settings.method = SolveMethod::Direct;
  auto unbounded = bentChain(0.0);
  auto bounded = bentChain(8000.0);
  Eigen::VectorXd a;
  reference->acceleration(reference->positions(), reference->velocities(), a);
  unbounded->acceleration(unbounded->positions(), unbounded->velocities(), a);
  bounded->acceleration(bounded->positions(), bounded->velocities(), a);
  const Eigen::VectorXd& expected = reference->solver().lambda();

  EXPECT_GT(unbounded->lastSolve().iterations, 10);  // plain CG needs more than the bound allows
  EXPECT_FALSE(unbounded->lastSolve().directFallback);
  EXPECT_EQ(bounded->lastSolve().iterations, 10);
  EXPECT_TRUE(bounded->lastSolve().directFallback);
  EXPECT_FALSE(bounded->lastSolve().failed);
  EXPECT_LT((bounded->solver().lambda() - expected).norm(), 1e-8 * expected.norm());

  // The next solve of the same structure goes straight to the direct solve.
  bounded->acceleration(bounded->positions(), bounded->velocities(), a);
  EXPECT_EQ(bounded->lastSolve().iterations, 0);
  EXPECT_TRUE(bounded->lastSolve().directFallback);
  EXPECT_LT((bounded->solver().lambda() - expected).norm(), 1e-8 * expected.norm());

  // A new constraint is a new structure: CG is tried again (402 entries:
  // 9 iterations within the bound).
  bounded->addConstraint(std::make_unique<RodConstraint>(3, 9, 0.5));
  bounded->acceleration(bounded->positions(), bounded->velocities(), a);
  EXPECT_EQ(bounded->lastSolve().iterations, 9);
  EXPECT_TRUE(bounded->lastSolve().directFallback);
}

TEST(ConstraintSolverMethods, CgWithinItsWorkBoundKeepsCg) {
  // The default bound (2e7 products) is far above what 200 rods need.
  auto s = bentChain(SolverSettings{}.maxCgWork);
  Eigen::VectorXd a;
  for (int k = 0; k < 2; ++k) {
    s->acceleration(s->positions(), s->velocities(), a);
    EXPECT_GT(s->lastSolve().iterations, 10);
    EXPECT_FALSE(s->lastSolve().directFallback);
  }
}

TEST(ConstraintSolverMethods, DirectFallbackIsCountedInTheStepAndNamedInAMessage) {
  auto s = bentChain(8000.0);
  auto integrator = makeIntegrator("symplectic-euler");
  const StepStats stats = s->step(*integrator, 1e-3);
  EXPECT_EQ(stats.directFallbacks, 1);  // one evaluation a step
  EXPECT_EQ(directFallbackMessage(200, s->solver().settings),
            "CG on 200 constraints passed its work bound (8000 products of J's entries in one solve): "
            "solved directly (LDLT) instead");
  SolverSettings negative;
  negative.maxCgWork = -1.0;
  EXPECT_THROW(negative.validate(), std::exception);
}

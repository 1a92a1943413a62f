#include "integrators/rattle.h"

#include <algorithm>
#include <cmath>

#include "linear/linear.h"
#include "particles/particle_system.h"

namespace particles {

struct RattleIntegrator::Impl {
  linear::ConstraintRows start, now;  // rows at x (the projection direction) and at the trial state
  linear::CgScratch cg;
  Eigen::VectorXd f, xStart, vPredicted, rhs, multiplier, diagonal, scatter;

  // Solves (J W Jᵀ + μ I) y = rhs for the rows' J by Jacobi-preconditioned
  // CG from y = 0, μ = kShift·max diag; rows with a zero diagonal (every
  // particle pinned) keep y = 0. The shift is the damped least squares of the
  // constraint solve's rank-loss branch (constraint_solver.cpp): where J W Jᵀ
  // has (nearly) lost rank, a wire and its tangent line, y stays within |rhs|/μ
  // instead of growing without bound; elsewhere each pass is off by μ/σ
  // relative, which the repeated passes of both projections remove.
  static constexpr double kShift = 1e-6;
  void solve(const linear::ConstraintRows& rows, const Eigen::VectorXd& w, StepStats& stats);
  // x += W Jᵀ y for the rows' J.
  void move(const linear::ConstraintRows& rows, const Eigen::VectorXd& w, const Eigen::VectorXd& y,
            Eigen::VectorXd& x);
  // Largest |C| over the constraints at x, relative to each one's length scale.
  static double worstViolation(const ParticleSystem& system, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
};

void RattleIntegrator::Impl::solve(const linear::ConstraintRows& rows, const Eigen::VectorXd& w,
                                   StepStats& stats) {
  const int m = rows.size();
  diagonal.resize(m);
  for (int k = 0; k < m; ++k) diagonal[k] = rows.diagonalOfJWJt(k, w);
  const double dead = 1e-14 * std::max(diagonal.maxCoeff(), 0.0);
  const double shift = kShift * diagonal.maxCoeff();
  for (int k = 0; k < m; ++k)
    if (diagonal[k] <= dead) rhs[k] = 0.0;
  auto apply = [&](const Eigen::VectorXd& y, Eigen::VectorXd& out) {
    rows.applyJWJt(w, y, out, scatter);
    for (int k = 0; k < m; ++k) out[k] = diagonal[k] <= dead ? 0.0 : out[k] + shift * y[k];
  };
  auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
    z.resize(m);
    for (int k = 0; k < m; ++k) z[k] = diagonal[k] <= dead ? 0.0 : r[k] / (diagonal[k] + shift);
  };
  linear::CgSettings settings;
  settings.tolerance = 1e-12;
  settings.maxIterations = 4 * m + 100;
  settings.curvatureFloor = 1e-14 * diagonal.maxCoeff();
  multiplier.setZero(m);
  const linear::CgResult result = linear::conjugateGradient(apply, precondition, rhs, multiplier, settings, cg);
  ++stats.solves;
  stats.cgIterations += result.iterations;
  stats.maxResidual = std::max(stats.maxResidual, result.relativeResidual);
  if (!multiplier.allFinite() || !std::isfinite(result.relativeResidual)) {
    multiplier.setZero(m);
    if (stats.failure == StepFailure::None) stats.failure = StepFailure::SolveFailed;
  }
}

void RattleIntegrator::Impl::move(const linear::ConstraintRows& rows, const Eigen::VectorXd& w,
                                  const Eigen::VectorXd& y, Eigen::VectorXd& x) {
  for (int k = 0; k < rows.size(); ++k)
    for (int e = rows.rowStart[k]; e < rows.rowStart[k + 1]; ++e) {
      const int p = rows.entryParticle[e];
      x.segment<2>(2 * p) += w[p] * y[k] * rows.J[e];
    }
}

double RattleIntegrator::Impl::worstViolation(const ParticleSystem& system, const Eigen::VectorXd& x,
                                              const Eigen::VectorXd& v) {
  const Phase s = system.phase(x, v);
  double worst = 0.0;
  for (const auto& c : system.constraints()) {
    const double scale = c->lengthScale() > 0.0 ? c->lengthScale() : 1.0;
    worst = std::max(worst, std::abs(c->violation(s)) / scale);
  }
  return worst;
}

namespace {
constexpr int kVelocityPasses = 3;
constexpr double kVelocityTolerance = 1e-12;  // |J v⁺|∞ against |v⁺|∞
}  // namespace

RattleIntegrator::RattleIntegrator() : impl_(std::make_unique<Impl>()) {}
RattleIntegrator::~RattleIntegrator() = default;

// kick → drift → project positions (SHAKE) → kick → project velocities.
StepStats RattleIntegrator::step(ParticleSystem& system, double dt) {
  Impl& s = *impl_;
  Eigen::VectorXd& x = positionsOf(system);
  Eigen::VectorXd& v = velocitiesOf(system);
  const Eigen::VectorXd& w = system.inverseMasses();
  const ConstraintList& constraints = system.constraints();
  auto kick = [&](double h) {
    for (int i = 0; i < system.size(); ++i) v.segment<2>(2 * i) += h * w[i] * s.f.segment<2>(2 * i);
  };
  StepStats stats;

  system.appliedForces(x, v, s.f);
  s.vPredicted = v;  // vⁿ, for the prediction of v⁺
  kick(0.5 * dt);
  s.xStart = x;
  if (!constraints.empty()) s.start.gather(system.phase(x, v), constraints);
  x += dt * v;

  // SHAKE: C(x̃ + W J(x)ᵀ Λ) = 0, Newton passes with J(x) for the unknown J(x⁺).
  // A pass that no longer shrinks the violation ends them: a constraint set
  // that has lost rank (a wire and its tangent line) meets C = 0 only to
  // second order, and the step is accepted if what is left is small.
  double previous = INFINITY;
  for (int pass = 0; !constraints.empty(); ++pass) {
    const double worst = Impl::worstViolation(system, x, v);
    if (worst <= positionTolerance) break;
    if (pass == maxPositionPasses || worst > 0.9 * previous) {
      if (worst > failureTolerance && stats.failure == StepFailure::None) stats.failure = StepFailure::SolveFailed;
      break;
    }
    previous = worst;
    s.now.gather(system.phase(x, v), constraints);
    s.rhs = -s.now.C;
    s.solve(s.start, w, stats);
    s.move(s.start, w, s.multiplier, x);
  }
  // v½, the constraint impulse included. The second kick's forces are taken
  // at the predicted v⁺ ≈ 2 v½ − vⁿ (error O(dt²)), as Verlet's are: forces
  // that depend on v (damping) would leave the step first order at v½. Forces
  // that do not are unchanged by it.
  v = (x - s.xStart) / dt;
  s.vPredicted = 2.0 * v - s.vPredicted;  // vⁿ was kept there

  system.appliedForces(x, s.vPredicted, s.f);
  kick(0.5 * dt);
  if (!constraints.empty()) {  // J(x⁺) v⁺ = 0 along W J(x⁺)ᵀ: passes until the shift's share is gone
    s.now.gather(system.phase(x, v), constraints);
    s.rhs.resize(s.now.size());
    for (int pass = 0; pass < kVelocityPasses; ++pass) {
      for (int k = 0; k < s.now.size(); ++k) s.rhs[k] = -s.now.rowTimes(k, v);
      if (s.rhs.lpNorm<Eigen::Infinity>() <= kVelocityTolerance * v.lpNorm<Eigen::Infinity>()) break;
      s.solve(s.now, w, stats);
      s.move(s.now, w, s.multiplier, v);
    }
  }
  lastStep_ = dt;
  system.addEvaluationStats(stats);
  return stats;
}

}  // namespace particles

#include "particles/constraint_solver.h"

#include <cmath>
#include <limits>

#include "particles/check.h"

namespace particles {

void SolverSettings::validate() const {
  requirePositive("solver tolerance", tolerance);
  if (maxIterations < 0)
    throw std::invalid_argument("solver max iterations must be >= 0, got " +
                                std::to_string(maxIterations));
  requireNonNegative("solver feedback stiffness k_s", stiffness);
  requireNonNegative("solver feedback damping k_d", damping);
}

// Gathers every constraint's row into the compressed arrays and forms
//   b = −J̇ q̇ − J W Q − k_s C − k_d Ċ   (one entry per constraint),
// and the diagonal of J W Jᵀ for the preconditioner. (The seed report's
// Algorithm 1 sizes d as 2n and uses J where J̇ belongs; b has m entries.)
void ConstraintSolver::gather(const Phase& s, const ConstraintList& constraints) {
  const int m = static_cast<int>(constraints.size());
  rowStart_.resize(m + 1);
  rowStart_[0] = 0;
  for (int k = 0; k < m; ++k)
    rowStart_[k + 1] = rowStart_[k] + static_cast<int>(constraints[k]->particles().size());
  const int entries = rowStart_[m];
  entryParticle_.resize(entries);
  J_.resize(entries);
  Jdot_.resize(entries);
  C_.resize(m);
  Cdot_.resize(m);
  b_.resize(m);
  diagonal_.resize(m);
  inverseMass_ = &s.inverseMass;
  for (int k = 0; k < m; ++k) {
    const Constraint& c = *constraints[k];
    ConstraintRow row;
    row.J = &J_[rowStart_[k]];
    row.Jdot = &Jdot_[rowStart_[k]];
    c.evaluate(s, row);
    C_[k] = row.C;
    Cdot_[k] = row.Cdot;
    for (int e = rowStart_[k], n = 0; e < rowStart_[k + 1]; ++e, ++n)
      entryParticle_[e] = c.particles()[n];
  }
}

void ConstraintSolver::applyOperator(const Eigen::VectorXd& y, Eigen::VectorXd& out) const {
  const int m = static_cast<int>(rowStart_.size()) - 1;
  const Eigen::VectorXd& w = *inverseMass_;
  // scatter = W Jᵀ y, then out = J scatter.
  Eigen::VectorXd& scatter = scatter_;
  scatter.setZero(2 * w.size());
  for (int k = 0; k < m; ++k)
    for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e)
      scatter.segment<2>(2 * entryParticle_[e]) += J_[e] * y[k];
  out.resize(m);
  for (int k = 0; k < m; ++k) {
    double sum = 0.0;
    for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e) {
      const int p = entryParticle_[e];
      sum += w[p] * J_[e].dot(scatter.segment<2>(2 * p));
    }
    out[k] = sum;
  }
}

void ConstraintSolver::addConstraintForces(const Phase& s, const ConstraintList& constraints,
                                           Eigen::VectorXd& f) {
  const int m = static_cast<int>(constraints.size());
  stats_ = SolveStats{};
  stats_.constraints = m;
  if (m == 0) return;
  gather(s, constraints);

  for (int k = 0; k < m; ++k) {
    double jdotv = 0.0, jwq = 0.0, diag = 0.0;
    for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e) {
      const int p = entryParticle_[e];
      const double w = s.inverseMass[p];
      jdotv += Jdot_[e].dot(s.velocity(p));
      jwq += w * J_[e].dot(f.segment<2>(2 * p));
      diag += w * J_[e].squaredNorm();
    }
    b_[k] = -jdotv - jwq - settings.stiffness * C_[k] - settings.damping * Cdot_[k];
    diagonal_[k] = diag;
  }

  if (!settings.warmStart || lambda_.size() != m || !lambda_.allFinite()) lambda_.setZero(m);
  double residual = 0.0;
  stats_.iterations = conjugateGradient(residual);
  stats_.residual = residual;
  if (!lambda_.allFinite()) lambda_.setZero();  // never hand NaN to the integrator

  for (int k = 0; k < m; ++k)
    for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e)
      f.segment<2>(2 * entryParticle_[e]) += J_[e] * lambda_[k];
}

// Conjugate gradient on A λ = b with A = J W Jᵀ symmetric positive
// semi-definite. Rows whose diagonal is zero (every particle in them pinned)
// are removed from the system with λ = 0. When A loses rank (a taut chain
// between two wires) b may have a part outside A's range; CG then meets a
// direction with pᵀAp ≈ 0, and stops there with the finite λ it has.
int ConstraintSolver::conjugateGradient(double& relativeResidual) {
  const int m = static_cast<int>(b_.size());
  const bool jacobi = settings.preconditioner == Preconditioner::Jacobi;
  const double diagMax = diagonal_.size() ? diagonal_.maxCoeff() : 0.0;
  const double dead = 1e-14 * diagMax;  // a diagonal this small is treated as zero
  auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
    z.resize(m);
    for (int k = 0; k < m; ++k)
      z[k] = diagonal_[k] <= dead ? 0.0 : (jacobi ? r[k] / diagonal_[k] : r[k]);
  };
  for (int k = 0; k < m; ++k)
    if (diagonal_[k] <= dead) lambda_[k] = 0.0, b_[k] = 0.0;

  const double bNorm = b_.norm();
  if (bNorm == 0.0 || diagMax == 0.0) {
    lambda_.setZero();
    relativeResidual = 0.0;
    return 0;
  }
  applyOperator(lambda_, Ap_);
  r_ = b_ - Ap_;
  precondition(r_, z_);
  p_ = z_;
  double rz = r_.dot(z_);
  const int cap = settings.maxIterations > 0 ? settings.maxIterations : 4 * m + 100;
  const double target = settings.tolerance * bNorm;
  int it = 0;
  while (it < cap && r_.norm() > target) {
    applyOperator(p_, Ap_);
    const double pAp = p_.dot(Ap_);
    if (!(pAp > 1e-14 * diagMax * p_.squaredNorm())) break;  // no curvature left
    const double alpha = rz / pAp;
    lambda_ += alpha * p_;
    r_ -= alpha * Ap_;
    precondition(r_, z_);
    const double rzNext = r_.dot(z_);
    p_ = z_ + (rzNext / rz) * p_;
    rz = rzNext;
    ++it;
  }
  relativeResidual = r_.norm() / bNorm;
  return it;
}

Eigen::MatrixXd ConstraintSolver::denseJ(int particleCount) const {
  const int m = static_cast<int>(rowStart_.size()) - 1;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, 2 * particleCount);
  for (int k = 0; k < m; ++k)
    for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e)
      J.block<1, 2>(k, 2 * entryParticle_[e]) += J_[e].transpose();
  return J;
}

Eigen::MatrixXd ConstraintSolver::denseJdot(int particleCount) const {
  const int m = static_cast<int>(rowStart_.size()) - 1;
  Eigen::MatrixXd Jd = Eigen::MatrixXd::Zero(m, 2 * particleCount);
  for (int k = 0; k < m; ++k)
    for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e)
      Jd.block<1, 2>(k, 2 * entryParticle_[e]) += Jdot_[e].transpose();
  return Jd;
}

}  // namespace particles

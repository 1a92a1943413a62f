#include "particles/constraint_solver.h"

#include <algorithm>
#include <array>
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
  // Any change in which particles the rows name invalidates the assembled
  // pattern; it is noticed here, while the rows are written anyway.
  bool changed = static_cast<int>(rowStart_.size()) != m + 1;
  rowStart_.resize(m + 1);
  rowStart_[0] = 0;
  for (int k = 0; k < m; ++k) {
    const int next = rowStart_[k] + static_cast<int>(constraints[k]->particles().size());
    changed |= rowStart_[k + 1] != next;
    rowStart_[k + 1] = next;
  }
  const int entries = rowStart_[m];
  changed |= static_cast<int>(entryParticle_.size()) != entries;
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
    for (int e = rowStart_[k], n = 0; e < rowStart_[k + 1]; ++e, ++n) {
      changed |= entryParticle_[e] != c.particles()[n];
      entryParticle_[e] = c.particles()[n];
    }
  }
  if (changed) patternValid_ = false;
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
  const double dead = 1e-14 * diagonal_.maxCoeff();  // a diagonal this small is treated as zero
  if (settings.method == SolveMethod::Direct && directSolve(dead, residual)) {
    stats_.iterations = 0;
  } else {
    if (settings.preconditioner == Preconditioner::IncompleteCholesky) {
      // A near-zero pivot (J W Jᵀ losing rank) would make the preconditioner
      // huge in one direction; CG then falls back to Jacobi for this solve.
      assemble(dead);
      if (!incompleteCholesky_) incompleteCholesky_ = std::make_unique<IncompleteCholesky>();
      incompleteCholesky_->compute(assembled_);
      ++stats_.factorizations;
      incompleteCholeskyUsable_ = incompleteCholesky_->info() == Eigen::Success &&
                                  incompleteCholesky_->matrixL().diagonal().cwiseAbs2().minCoeff() > 1e-10;
    }
    stats_.iterations = conjugateGradient(dead, residual);
  }
  stats_.residual = residual;
  if (!lambda_.allFinite() || !std::isfinite(residual)) {
    stats_.failed = true;  // reported through StepStats; never hand NaN to the integrator
    lambda_.setZero();
  }

  for (int k = 0; k < m; ++k)
    for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e)
      f.segment<2>(2 * entryParticle_[e]) += J_[e] * lambda_[k];
}

// Conjugate gradient on A λ = b with A = J W Jᵀ symmetric positive
// semi-definite. Rows whose diagonal is zero (every particle in them pinned)
// are removed from the system with λ = 0. When A loses rank (a taut chain
// between two wires) b may have a part outside A's range; CG then meets a
// direction with pᵀAp ≈ 0, and stops there with the finite λ it has.
int ConstraintSolver::conjugateGradient(double dead, double& relativeResidual) {
  const int m = static_cast<int>(b_.size());
  const Preconditioner preconditioner =
      settings.preconditioner == Preconditioner::IncompleteCholesky && !incompleteCholeskyUsable_
          ? Preconditioner::Jacobi
          : settings.preconditioner;
  permuted_.resize(m);
  const double diagMax = diagonal_.size() ? diagonal_.maxCoeff() : 0.0;
  auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
    if (preconditioner == Preconditioner::IncompleteCholesky) {
      // The factor is of the permuted matrix (see assemble()).
      for (int k = 0; k < m; ++k) permuted_[order_[k]] = r[k];
      permutedSolution_ = incompleteCholesky_->solve(permuted_);
      z.resize(m);
      for (int k = 0; k < m; ++k) z[k] = diagonal_[k] <= dead ? 0.0 : permutedSolution_[order_[k]];
      return;
    }
    z.resize(m);
    for (int k = 0; k < m; ++k)
      z[k] = diagonal_[k] <= dead ? 0.0
                                  : (preconditioner == Preconditioner::Jacobi ? r[k] / diagonal_[k] : r[k]);
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

// (J W Jᵀ)_kl = Σ_p w_p J_k,p · J_l,p over the particles p that constraints k
// and l share. The pattern (which pairs of entries meet in which slot) depends
// only on which particles each constraint names, so it is built once per
// constraint structure, already permuted by an AMD fill-reducing ordering and
// stored as the upper triangle: SimplicialLDLT with NaturalOrdering then
// factorises it in place, with no per-solve permutation or copy. Each solve
// only sums the pairs into the values.
void ConstraintSolver::assemble(double dead) {
  const int m = static_cast<int>(rowStart_.size()) - 1;
  if (!patternValid_) {  // gather() clears it when the rows name other particles
    // Every pair of entries on the same particle meets in slot (k, l).
    const int entries = rowStart_[m];
    std::vector<int> constraintOf(entries);
    for (int k = 0; k < m; ++k)
      for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e) constraintOf[e] = k;
    int particles = 0;
    for (int p : entryParticle_) particles = std::max(particles, p + 1);
    std::vector<std::vector<int>> byParticle(particles);
    for (int e = 0; e < entries; ++e) byParticle[entryParticle_[e]].push_back(e);
    std::vector<std::array<int, 4>> pairs;  // k, l, e1, e2
    std::vector<Eigen::Triplet<double>> pattern;
    for (int k = 0; k < m; ++k) pattern.emplace_back(k, k, 1.0);  // every diagonal, even empty rows
    for (const auto& list : byParticle)
      for (int e1 : list)
        for (int e2 : list)
          if (constraintOf[e1] != constraintOf[e2]) {  // diagonals come from diagonal_
            pairs.push_back({constraintOf[e1], constraintOf[e2], e1, e2});
            pattern.emplace_back(constraintOf[e1], constraintOf[e2], 1.0);
          }
    SparseMatrix symmetric(m, m);
    symmetric.setFromTriplets(pattern.begin(), pattern.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int>()(symmetric, inverse);
    order_.resize(m);  // constraint k sits at order_[k]: the inverse of AMD's permutation
    for (int k = 0; k < m; ++k) order_[inverse.indices()[k]] = k;

    // Upper triangle in the permuted numbering: a pair is visited in both
    // orders, keep the upper one.
    pattern.clear();
    std::vector<std::array<int, 4>> kept;
    for (const auto& q : pairs) {
      const int r = order_[q[0]], c = order_[q[1]];
      if (r > c) continue;
      kept.push_back({r, c, q[2], q[3]});
      pattern.emplace_back(r, c, 1.0);
    }
    for (int k = 0; k < m; ++k) pattern.emplace_back(k, k, 1.0);
    assembled_.resize(m, m);
    assembled_.setFromTriplets(pattern.begin(), pattern.end());
    assembled_.makeCompressed();
    auto slot = [&](int r, int c) {
      const int* begin = assembled_.innerIndexPtr() + assembled_.outerIndexPtr()[c];
      const int* end = assembled_.innerIndexPtr() + assembled_.outerIndexPtr()[c + 1];
      return static_cast<int>(std::lower_bound(begin, end, r) - assembled_.innerIndexPtr());
    };
    std::sort(kept.begin(), kept.end(),
              [&](const auto& a, const auto& b) { return slot(a[0], a[1]) < slot(b[0], b[1]); });
    pairStart_.assign(assembled_.nonZeros() + 1, 0);
    pairFirst_.resize(kept.size());
    pairSecond_.resize(kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i) {
      ++pairStart_[slot(kept[i][0], kept[i][1]) + 1];
      pairFirst_[i] = kept[i][2];
      pairSecond_[i] = kept[i][3];
    }
    for (std::size_t k = 1; k < pairStart_.size(); ++k) pairStart_[k] += pairStart_[k - 1];
    diagonalSlot_.resize(m);
    for (int k = 0; k < m; ++k) diagonalSlot_[k] = slot(order_[k], order_[k]);
    patternValid_ = true;
    ldltAnalysed_ = false;
  }
  const Eigen::VectorXd& w = *inverseMass_;
  double* value = assembled_.valuePtr();
  for (int slotIndex = 0; slotIndex < assembled_.nonZeros(); ++slotIndex) {
    double sum = 0.0;
    for (int i = pairStart_[slotIndex]; i < pairStart_[slotIndex + 1]; ++i) {
      const int e1 = pairFirst_[i], e2 = pairSecond_[i];
      const double term = w[entryParticle_[e1]] * J_[e1].dot(J_[e2]);  // e1, e2 on one particle
      sum += term;
    }
    value[slotIndex] = sum;
  }
  // The diagonal Σ w_p |J_k,p|² is diagonal_, formed with b. A dead row has
  // zero off-diagonals too (each of its entries has w = 0 or J = 0); a unit
  // diagonal with b = 0 gives it λ = 0.
  for (int k = 0; k < m; ++k) value[diagonalSlot_[k]] = diagonal_[k] <= dead ? 1.0 : diagonal_[k];
}

// LDLᵀ of the assembled matrix. A pivot that is tiny next to the largest
// diagonal (≤ kRankLossPivot·max diag) means J W Jᵀ has lost rank: a taut
// chain between two wires, or a bead on a wire and its tangent line, where b
// also has a part outside the range of J W Jᵀ (the constraints are
// inconsistent at the velocity level, e.g. by |v|²/r). The exact solve would
// hand back λ ~ b/pivot, unbounded as the pivot goes to zero. The matrix is
// then refactorised with a shift, (J W Jᵀ + μ I) λ = b with
// μ = kRankLossShift·max diag: damped least squares (Levenberg–Marquardt),
// whose λ stays within |b|/μ and tends to the least-squares solution as μ → 0.
// Its effect on accuracy: directions of J W Jᵀ with eigenvalue σ are solved
// with relative error μ/(σ + μ), so only the (nearly) dependent directions
// are changed noticeably; a well-posed system never takes this branch.
bool ConstraintSolver::directSolve(double dead, double& relativeResidual) {
  constexpr double kRankLossPivot = 1e-10, kRankLossShift = 1e-6;
  const int m = static_cast<int>(b_.size());
  for (int k = 0; k < m; ++k)
    if (diagonal_[k] <= dead) b_[k] = 0.0;
  assemble(dead);
  if (!ldlt_) ldlt_ = std::make_unique<InPlaceLdlt>();
  if (!ldltAnalysed_) {
    ldlt_->analyzePattern(assembled_);
    ldltAnalysed_ = true;
  }
  const double diagMax = diagonal_.maxCoeff();
  ldlt_->setShift(0.0);
  ldlt_->factorizeInPlace(assembled_);
  ++stats_.factorizations;
  if (ldlt_->info() != Eigen::Success || !(ldlt_->pivots().minCoeff() > kRankLossPivot * diagMax)) {
    ldlt_->setShift(kRankLossShift * diagMax);
    ldlt_->factorizeInPlace(assembled_);
    ++stats_.factorizations;
    stats_.regularized = true;
    if (ldlt_->info() != Eigen::Success) return false;
  }
  permuted_.resize(m);
  for (int k = 0; k < m; ++k) permuted_[order_[k]] = b_[k];
  permutedSolution_ = ldlt_->solve(permuted_);
  for (int k = 0; k < m; ++k) lambda_[k] = permutedSolution_[order_[k]];
  // Residual in the permuted numbering, with the assembled matrix.
  const double bNorm = permuted_.norm();
  if (bNorm == 0.0) {
    relativeResidual = 0.0;
  } else {
    Ap_.noalias() = assembled_.selfadjointView<Eigen::Upper>() * permutedSolution_;
    relativeResidual = (permuted_ - Ap_).norm() / bNorm;
  }
  return true;
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

#include "particles/constraint_solver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/IterativeLinearSolvers>

#include "constraints/rod_chain.h"
#include "linear/linear.h"
#include "particles/cancel.h"
#include "particles/check.h"

namespace particles {

void SolverSettings::validate() const {
  requirePositive("solver tolerance", tolerance);
  if (maxIterations < 0)
    throw std::invalid_argument("solver max iterations must be >= 0, got " +
                                std::to_string(maxIterations));
  requireNonNegative("solver feedback stiffness k_s", stiffness);
  requireNonNegative("solver feedback damping k_d", damping);
  requireNonNegative("solver CG work bound", maxCgWork);
}

std::string directFallbackMessage(int constraints, const SolverSettings& settings) {
  char bound[32];
  std::snprintf(bound, sizeof bound, "%g", settings.maxCgWork);
  return "CG on " + std::to_string(constraints) + " constraints passed its work bound (" + bound +
         " products of J's entries in one solve): solved directly (LDLT) instead";
}

struct ConstraintSolver::Workspace {
  linear::ConstraintRows rows;
  Eigen::VectorXd diagonal;  // diag(J W Jᵀ), the Jacobi preconditioner
  double diagonalMax = 0.0;  // its largest entry
  const Eigen::VectorXd* inverseMass = nullptr;
  linear::CgScratch cg;
  mutable Eigen::VectorXd scatter;  // W Jᵀ y inside applyOperator

  // Assembled P (J W Jᵀ) Pᵀ (P an AMD ordering). Value s of the stored
  // triangle is Σ w_p J_e1·J_e2 over the pairs pairStart[s] .. pairStart[s+1]−1,
  // e1 and e2 entries of two constraints on one particle p.
  linear::SymmetricPattern pattern;
  std::vector<int> pairStart, pairFirst, pairSecond, diagonalSlot;
  bool patternValid = false;
  linear::Ldlt ldlt;
  using IncompleteCholesky = Eigen::IncompleteCholesky<double, Eigen::Upper, Eigen::NaturalOrdering<int>>;
  std::unique_ptr<IncompleteCholesky> incompleteCholesky;  // made on first use
  bool incompleteCholeskyUsable = false;
  Eigen::VectorXd stored, storedSolution, product;
  bool cgPastWorkBound = false;  // CG passed maxCgWork on this structure: solve directly

  // A chain: every constraint shares particles only with the one before and
  // the one after it in the list, so J W Jᵀ is tridiagonal in the list's
  // own order and the direct solve is linear/tridiagonal.h's O(m) LDLᵀ, with
  // no ordering, sparse pattern or sparse factor. Off-diagonal k, (k, k + 1),
  // is Σ w_p J_e1·J_e2 over the pairs chainPairStart[k] .. chainPairStart[k+1]−1.
  bool chainKnown = false, chain = false;
  std::vector<int> chainPairStart, chainPairFirst, chainPairSecond;
  std::vector<double> chainDiagonal, chainUpper;
  linear::Tridiagonal tridiagonal;
  // A chain whose every constraint is a rod: its rows, b and upper band come
  // from RodChain's own pass (chainUpperFormed: this evaluation's did).
  // chainFactorised: and factorised it (no dead row), for directSolve to use once.
  bool rodChainKnown = false, rodChainBuilt = false, chainUpperFormed = false, chainFactorised = false;
  RodChain rodChain;
};

namespace {

// A row whose diagonal is at most this times the largest is treated as zero (dead).
constexpr double kDeadDiagonal = 1e-14;

// Every pair of entries e1, e2 of two constraints k < l on one particle: the
// pairs that make the off-diagonal entries (J W Jᵀ)_kl.
struct EntryPair {
  int k, l, e1, e2;
};
std::vector<EntryPair> entryPairs(const linear::ConstraintRows& rows) {
  const int m = rows.size();
  std::vector<int> constraintOf(rows.entries());
  for (int k = 0; k < m; ++k)
    for (int e = rows.rowStart[k]; e < rows.rowStart[k + 1]; ++e) constraintOf[e] = k;
  int particles = 0;
  for (int p : rows.entryParticle) particles = std::max(particles, p + 1);
  std::vector<std::vector<int>> byParticle(particles);
  for (int e = 0; e < rows.entries(); ++e) byParticle[rows.entryParticle[e]].push_back(e);
  std::vector<EntryPair> pairs;
  for (const auto& list : byParticle)
    for (int e1 : list)
      for (int e2 : list)
        if (constraintOf[e1] < constraintOf[e2]) pairs.push_back({constraintOf[e1], constraintOf[e2], e1, e2});
  return pairs;
}

// Σ w_p J_e1·J_e2 over pairs [begin, end) (e1, e2 on one particle p).
double pairSum(const linear::ConstraintRows& rows, const Eigen::VectorXd& inverseMass, const std::vector<int>& first,
               const std::vector<int>& second, int begin, int end) {
  double sum = 0.0;
  for (int i = begin; i < end; ++i)
    sum += inverseMass[rows.entryParticle[first[i]]] * rows.J[first[i]].dot(rows.J[second[i]]);
  return sum;
}

}  // namespace

ConstraintSolver::ConstraintSolver() : work_(std::make_unique<Workspace>()) {}
ConstraintSolver::~ConstraintSolver() = default;
ConstraintSolver::ConstraintSolver(ConstraintSolver&&) noexcept = default;
ConstraintSolver& ConstraintSolver::operator=(ConstraintSolver&&) noexcept = default;

void ConstraintSolver::applyOperator(const Eigen::VectorXd& y, Eigen::VectorXd& out) const {
  work_->rows.applyJWJt(*work_->inverseMass, y, out, work_->scatter);
}

// Gathers the rows and forms
//   b = −J̇ q̇ − J W Q − k_s C − k_d Ċ   (one entry per constraint),
// and the diagonal of J W Jᵀ for the preconditioner. (The seed report's
// Algorithm 1 sizes d as 2n and uses J where J̇ belongs; b has m entries.)
void ConstraintSolver::addConstraintForces(const Phase& s, const ConstraintList& constraints,
                                           Eigen::VectorXd& f) {
  const int m = static_cast<int>(constraints.size());
  stats_ = SolveStats{};
  stats_.constraints = m;
  if (m == 0) return;
  Workspace& w = *work_;
  w.inverseMass = &s.inverseMass;
  const bool rods = formSystem(s, constraints, f);
  stats_.chainPass = rods;

  if (!settings.warmStart || lambda_.size() != m || !lambda_.allFinite()) lambda_.setZero(m);
  double residual = 0.0;
  const double dead = kDeadDiagonal * w.diagonalMax;
  const bool direct = settings.method == SolveMethod::Direct || w.cgPastWorkBound;
  if (direct && directSolve(dead, residual)) {
    stats_.iterations = 0;
    stats_.directFallback = settings.method != SolveMethod::Direct;
  } else {
    if (settings.preconditioner == Preconditioner::IncompleteCholesky) {
      // A near-zero pivot (J W Jᵀ losing rank) would make the preconditioner
      // huge in one direction; CG then falls back to Jacobi for this solve.
      assemble(dead);
      if (!w.incompleteCholesky) w.incompleteCholesky = std::make_unique<Workspace::IncompleteCholesky>();
      w.incompleteCholesky->compute(w.pattern.matrix());
      ++stats_.factorizations;
      w.incompleteCholeskyUsable = w.incompleteCholesky->info() == Eigen::Success &&
                                   w.incompleteCholesky->matrixL().diagonal().cwiseAbs2().minCoeff() > 1e-10;
    }
    bool pastWorkBound = false;
    stats_.iterations = conjugateGradient(dead, residual, pastWorkBound);
    if (pastWorkBound && directSolve(dead, residual)) {  // its λ replaces CG's unconverged one
      w.cgPastWorkBound = true;
      stats_.directFallback = true;
    }
  }
  stats_.residual = residual;
  if (!lambda_.allFinite() || !std::isfinite(residual)) {
    stats_.failed = true;  // reported through StepStats; never hand NaN to the integrator
    lambda_.setZero();
  }
  if (rods) w.rodChain.addJtTimes(w.rows, lambda_, f);
  else w.rows.addJtTimes(lambda_, f);
  if (w.chainKnown && w.chain && !w.rodChainKnown) {  // the next evaluations take the rods' own pass
    w.rodChainKnown = true;
    w.rodChainBuilt = w.rodChain.build(constraints);
  }
}

// The rows, b and diag(J W Jᵀ) at s (with forces f): by the chain of rods'
// own pass (constraints/rod_chain.h, which also forms the chain's upper band)
// when the direct solve has found one, else by the generic gather. Returns
// whether the rods' pass formed them.
bool ConstraintSolver::formSystem(const Phase& s, const ConstraintList& constraints, const Eigen::VectorXd& f) {
  Workspace& w = *work_;
  const bool direct = settings.method == SolveMethod::Direct || w.cgPastWorkBound;
  if (direct && w.rodChainBuilt) {
    const RodChain::Formed formed =
        w.rodChain.form(s, constraints, f, settings.stiffness, settings.damping,
                        {w.rows, b_, w.diagonal, w.chainDiagonal, w.chainUpper, w.tridiagonal});
    w.chainUpperFormed = formed.valid;
    if (formed.valid) {
      w.diagonalMax = formed.largest;
      // The pass factorised J W Jᵀ as formed; a dead row would have had its
      // diagonal replaced first (assembleChain), so the solve factorises again.
      w.chainFactorised = !(formed.smallest <= kDeadDiagonal * formed.largest);
      return true;
    }
    w.rodChainKnown = w.rodChainBuilt = false;  // not the rods it was built from: gathered below, built again
  }
  w.chainUpperFormed = w.chainFactorised = false;
  if (w.rows.gather(s, constraints))
    w.patternValid = w.cgPastWorkBound = w.chainKnown = w.rodChainKnown = w.rodChainBuilt = false;
  w.diagonalMax = w.rows.rhsAndDiagonal(s.inverseMass, s.v, f, settings.stiffness, settings.damping, b_, w.diagonal);
  return false;
}

// Conjugate gradient on A λ = b with A = J W Jᵀ symmetric positive
// semi-definite, applied matrix-free. Rows whose diagonal is zero (every
// particle in them pinned) are removed from the system with λ = 0. When A
// loses rank (a taut chain between two wires) b may have a part outside A's
// range; CG then meets a direction with pᵀAp ≈ 0 and stops there with the
// finite λ it has.
int ConstraintSolver::conjugateGradient(double dead, double& relativeResidual, bool& pastWorkBound) {
  Workspace& w = *work_;
  const int m = static_cast<int>(b_.size());
  const Preconditioner preconditioner =
      settings.preconditioner == Preconditioner::IncompleteCholesky && !w.incompleteCholeskyUsable
          ? Preconditioner::Jacobi
          : settings.preconditioner;
  const Eigen::VectorXd& diagonal = w.diagonal;
  auto precondition = [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) {
    z.resize(m);
    if (preconditioner == Preconditioner::IncompleteCholesky) {
      // The factor is of the stored, permuted matrix (see assemble()).
      w.pattern.toStored(r, w.stored);
      w.storedSolution = w.incompleteCholesky->solve(w.stored);
      for (int k = 0; k < m; ++k) z[k] = diagonal[k] <= dead ? 0.0 : w.storedSolution[w.pattern.order()[k]];
      return;
    }
    for (int k = 0; k < m; ++k)
      z[k] = diagonal[k] <= dead ? 0.0
                                 : (preconditioner == Preconditioner::Jacobi ? r[k] / diagonal[k] : r[k]);
  };
  auto apply = [&](const Eigen::VectorXd& y, Eigen::VectorXd& out) { applyOperator(y, out); };
  for (int k = 0; k < m; ++k)
    if (diagonal[k] <= dead) lambda_[k] = 0.0, b_[k] = 0.0;

  linear::CgSettings cg;
  cg.tolerance = settings.tolerance;
  cg.maxIterations = settings.maxIterations > 0 ? settings.maxIterations : 4 * m + 100;
  // The work bound in iterations: each applies J and Jᵀ once.
  const double perIteration = 2.0 * std::max<std::size_t>(1, w.rows.J.size());
  const bool bounded = settings.maxCgWork > 0.0 && settings.maxCgWork / perIteration < cg.maxIterations;
  if (bounded) cg.maxIterations = std::max(1, static_cast<int>(settings.maxCgWork / perIteration));
  cg.curvatureFloor = 1e-14 * diagonal.maxCoeff();
  const linear::CgResult result = linear::conjugateGradient(apply, precondition, b_, lambda_, cg, w.cg);
  relativeResidual = result.relativeResidual;
  pastWorkBound = bounded && result.iterations >= cg.maxIterations && !(relativeResidual <= settings.tolerance) &&
                  !cancelRequested();
  return result.iterations;
}

// (J W Jᵀ)_kl = Σ_p w_p J_k,p · J_l,p over the particles p that constraints k
// and l share. The pattern (which pairs of entries meet in which slot) depends
// only on which particles each constraint names, so it is built once per
// constraint structure, AMD-ordered, as SymmetricPattern stores it; each solve
// only sums the pairs into the values.
void ConstraintSolver::assemble(double dead) {
  Workspace& w = *work_;
  const linear::ConstraintRows& rows = w.rows;
  const int m = rows.size();
  if (!w.patternValid) {  // gather() reports when the rows name other particles
    const std::vector<EntryPair> pairs = entryPairs(rows);
    w.pattern.reset(m);
    for (const EntryPair& pair : pairs) w.pattern.add(pair.k, pair.l);  // diagonals come from diagonal
    w.pattern.finish(linear::SymmetricPattern::Ordering::Amd);
    std::vector<int> slotOf(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) slotOf[i] = w.pattern.slot(pairs[i].k, pairs[i].l);
    std::vector<std::size_t> bySlot(pairs.size());
    for (std::size_t i = 0; i < bySlot.size(); ++i) bySlot[i] = i;
    std::stable_sort(bySlot.begin(), bySlot.end(), [&](std::size_t a, std::size_t b) { return slotOf[a] < slotOf[b]; });
    w.pairStart.assign(w.pattern.nonZeros() + 1, 0);
    w.pairFirst.resize(pairs.size());
    w.pairSecond.resize(pairs.size());
    for (std::size_t i = 0; i < bySlot.size(); ++i) {
      ++w.pairStart[slotOf[bySlot[i]] + 1];
      w.pairFirst[i] = pairs[bySlot[i]].e1;
      w.pairSecond[i] = pairs[bySlot[i]].e2;
    }
    for (std::size_t s = 1; s < w.pairStart.size(); ++s) w.pairStart[s] += w.pairStart[s - 1];
    w.diagonalSlot.resize(m);
    for (int k = 0; k < m; ++k) w.diagonalSlot[k] = w.pattern.slot(k, k);
    w.patternValid = true;
    w.ldlt.forgetAnalysis();
  }
  double* value = w.pattern.values();
  for (int s = 0; s < w.pattern.nonZeros(); ++s)
    value[s] = pairSum(rows, *w.inverseMass, w.pairFirst, w.pairSecond, w.pairStart[s], w.pairStart[s + 1]);
  // The diagonal Σ w_p |J_k,p|² is `diagonal`, formed with b. A dead row has
  // zero off-diagonals too (each of its entries has w = 0 or J = 0); a unit
  // diagonal with b = 0 gives it λ = 0.
  for (int k = 0; k < m; ++k) value[w.diagonalSlot[k]] = w.diagonal[k] <= dead ? 1.0 : w.diagonal[k];
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
  Workspace& w = *work_;
  const int m = static_cast<int>(b_.size());
  // The rods' pass factorised the chain already when no row was dead (formSystem).
  const bool factorisedInPass = w.chainFactorised;
  w.chainFactorised = false;
  if (!factorisedInPass)
    for (int k = 0; k < m; ++k)
      if (w.diagonal[k] <= dead) b_[k] = 0.0;
  if (!w.chainKnown) findChain();
  const double diagMax = w.diagonalMax;
  // LDLᵀ of J W Jᵀ + shift·I: the chain's tridiagonal one, or the sparse one of the assembled matrix.
  auto factorize = [&](double shift) {
    ++stats_.factorizations;
    return w.chain ? w.tridiagonal.factorize(w.chainDiagonal, w.chainUpper, shift)
                   : w.ldlt.factorize(w.pattern.matrix(), shift);
  };
  auto smallestPivot = [&] { return w.chain ? w.tridiagonal.smallestPivot() : w.ldlt.smallestPivot(); };
  if (!w.chain) assemble(dead);
  else if (!factorisedInPass) assembleChain(dead);
  bool factorised = factorisedInPass ? (++stats_.factorizations, w.tridiagonal.usable()) : factorize(0.0);
  const bool rankLost = !factorised || !(smallestPivot() > kRankLossPivot * diagMax);
  if (rankLost) {
    factorised = factorize(kRankLossShift * diagMax);
    stats_.regularized = true;
    if (!factorised) return false;
  }
  if (w.chain) {
    relativeResidual = factorisedInPass && !rankLost  // b went forward in the pass
                           ? w.tridiagonal.backSubstitute(b_, lambda_, w.chainDiagonal, w.chainUpper)
                           : w.tridiagonal.solve(b_, lambda_, w.chainDiagonal, w.chainUpper);
    return true;
  }
  w.pattern.toStored(b_, w.stored);
  w.ldlt.solve(w.stored, w.storedSolution);
  w.pattern.fromStored(w.storedSolution, lambda_);
  // Residual in the stored numbering, with the assembled matrix.
  const double bNorm = w.stored.norm();
  if (bNorm == 0.0) {
    relativeResidual = 0.0;
  } else {
    w.pattern.multiplyStored(w.storedSolution, w.product);
    relativeResidual = (w.stored - w.product).norm() / bNorm;
  }
  return true;
}

// Whether the rows form a chain (Workspace::chain), and the chain's pairs of
// entries per off-diagonal, once per constraint structure.
void ConstraintSolver::findChain() {
  Workspace& w = *work_;
  const int m = w.rows.size();
  const std::vector<EntryPair> pairs = entryPairs(w.rows);
  w.chainKnown = true;
  w.chain = std::all_of(pairs.begin(), pairs.end(), [](const EntryPair& p) { return p.l == p.k + 1; });
  if (!w.chain) return;
  w.chainPairStart.assign(static_cast<std::size_t>(std::max(m, 1)), 0);
  w.chainPairFirst.resize(pairs.size());
  w.chainPairSecond.resize(pairs.size());
  for (const EntryPair& p : pairs) ++w.chainPairStart[static_cast<std::size_t>(p.k + 1)];
  for (std::size_t k = 1; k < w.chainPairStart.size(); ++k) w.chainPairStart[k] += w.chainPairStart[k - 1];
  std::vector<int> fill(w.chainPairStart.begin(), w.chainPairStart.end());
  for (const EntryPair& p : pairs) {  // in the order entryPairs gives them, as assemble() sums them
    const int at = fill[static_cast<std::size_t>(p.k)]++;
    w.chainPairFirst[static_cast<std::size_t>(at)] = p.e1;
    w.chainPairSecond[static_cast<std::size_t>(at)] = p.e2;
  }
}

// The chain's J W Jᵀ as its diagonal and its upper band (the latter already
// formed when the rods' pass ran, formSystem); a dead row (diagonal
// at most `dead`) gets a unit diagonal and, with b = 0, λ = 0, as in assemble().
void ConstraintSolver::assembleChain(double dead) {
  Workspace& w = *work_;
  const int m = w.rows.size();
  w.chainDiagonal.resize(static_cast<std::size_t>(m));
  w.chainUpper.resize(static_cast<std::size_t>(std::max(m - 1, 0)));
  const double* diagonal = w.diagonal.data();
  double *chainDiagonal = w.chainDiagonal.data(), *upper = w.chainUpper.data();
  for (int k = 0; k < m; ++k) chainDiagonal[k] = diagonal[k] <= dead ? 1.0 : diagonal[k];
  if (w.chainUpperFormed) return;
  const int* pairStart = w.chainPairStart.data();
  for (int k = 0; k + 1 < m; ++k)
    upper[k] = pairSum(w.rows, *w.inverseMass, w.chainPairFirst, w.chainPairSecond, pairStart[k], pairStart[k + 1]);
}

Eigen::MatrixXd ConstraintSolver::denseJ(int particleCount) const { return work_->rows.denseJ(particleCount); }
Eigen::MatrixXd ConstraintSolver::denseJdot(int particleCount) const { return work_->rows.denseJdot(particleCount); }

}  // namespace particles

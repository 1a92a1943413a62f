#include "particles/integrators/implicit_euler.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "particles/check.h"
#include "particles/particle_system.h"

namespace particles {

void ImplicitEulerSettings::validate() const {
  requireNonNegative("implicit stabilization beta", stabilization);
  if (constraintPasses < 1)
    throw std::invalid_argument("implicit constraint passes must be >= 1, got " +
                                std::to_string(constraintPasses));
  requirePositive("implicit compliance", compliance);
  requirePositive("implicit CG tolerance", cgTolerance);
  if (cgMaxIterations < 1)
    throw std::invalid_argument("implicit CG max iterations must be >= 1, got " +
                                std::to_string(cgMaxIterations));
}

void ImplicitEulerIntegrator::requireJacobians(const ParticleSystem& system) {
  const auto& forces = system.forceObjects();
  for (std::size_t k = 0; k < forces.size(); ++k)
    if (!forces[k]->hasJacobians())
      throw std::invalid_argument(std::string("implicit-euler needs force Jacobians, but force #") +
                                  std::to_string(k) + " ('" + forces[k]->type() +
                                  "') provides none");
}

// Rows of J and J̇ at (x, v), in the compressed layout of ConstraintSolver.
void ImplicitEulerIntegrator::gatherConstraints(ParticleSystem& system, const Eigen::VectorXd& x,
                                                const Eigen::VectorXd& v) {
  const ConstraintList& constraints = system.constraints();
  const Phase s = system.phase(x, v);
  const int m = static_cast<int>(constraints.size());
  rowStart_.resize(m + 1);
  rowStart_[0] = 0;
  for (int k = 0; k < m; ++k)
    rowStart_[k + 1] = rowStart_[k] + static_cast<int>(constraints[k]->particles().size());
  entryParticle_.resize(rowStart_[m]);
  J_.resize(rowStart_[m]);
  Jdot_.resize(rowStart_[m]);
  C_.resize(m);
  for (int k = 0; k < m; ++k) {
    ConstraintRow row;
    row.J = &J_[rowStart_[k]];
    row.Jdot = &Jdot_[rowStart_[k]];
    constraints[k]->evaluate(s, row);
    C_[k] = row.C;
    for (int e = rowStart_[k], i = 0; e < rowStart_[k + 1]; ++e, ++i)
      entryParticle_[e] = constraints[k]->particles()[i];
  }
}

double ImplicitEulerIntegrator::worstRelativeViolation(ParticleSystem& system,
                                                      const Eigen::VectorXd& x,
                                                      const Eigen::VectorXd& v) const {
  const Phase s = system.phase(x, v);
  const Eigen::VectorXd& w = system.inverseMasses();
  double worst = 0.0;
  for (const auto& c : system.constraints()) {
    // A row whose particles are all pinned is −ν = 0 in the solve: no pass can
    // change its violation, so it must not keep the passes going.
    const std::vector<int>& ps = c->particles();
    if (std::all_of(ps.begin(), ps.end(), [&](int p) { return w[p] == 0.0; })) continue;
    const double scale = c->lengthScale();
    worst = std::max(worst, c->violation(s) / (scale > 0.0 ? scale : 1.0));
  }
  return worst;
}

bool ImplicitEulerIntegrator::patternMatches(int n, const Eigen::VectorXd& inverseMass,
                                             bool withConstraints, bool direct) const {
  if (!analysed_ || withConstraints != cachedWithConstraints_ || direct != cachedDirect_) return false;
  if (static_cast<int>(cachedPinned_.size()) != n) return false;
  for (int i = 0; i < n; ++i)
    if (cachedPinned_[i] != (inverseMass[i] == 0.0)) return false;
  // Each triplet's position is checked while fillValues() scatters it.
  if (dfdx_.size() != xRow_.size() || dfdv_.size() != vRow_.size()) return false;
  if (withConstraints && (rowStart_ != cachedRowStart_ || entryParticle_ != cachedEntryParticle_))
    return false;
  return true;
}

// The KKT matrix: A on the 2n velocity unknowns, then one row per constraint,
// stored as the upper triangle in a permuted numbering (unknown i at order_[i]):
// an AMD fill-reducing order for the direct solve, so that the LDLᵀ
// factorises the stored matrix in place without a per-step permuted copy, and
// the identity for CG, whose products are faster in the mesh's own order.
// Every value's destination in matrix_.valuePtr() is recorded so that
// fillValues() is a scatter, with no search and no allocation.
void ImplicitEulerIntegrator::buildPattern(ParticleSystem& system, bool withConstraints, bool direct) {
  const Eigen::VectorXd& inverseMass = system.inverseMasses();
  const int n = system.size(), dofs = 2 * n;
  const int m = withConstraints ? static_cast<int>(rowStart_.size()) - 1 : 0;
  auto free = [&](int dof) { return inverseMass[dof / 2] != 0.0; };

  // Every (row, column) of the symmetric matrix, in the original numbering.
  Triplets pattern;
  pattern.reserve(dofs + dfdx_.size() + dfdv_.size() + 2 * J_.size() + m);
  for (int d = 0; d < dofs; ++d) pattern.emplace_back(d, d, 1.0);
  for (const Triplets* list : {&dfdx_, &dfdv_})
    for (const auto& t : *list)
      if (free(t.row()) && free(t.col())) pattern.emplace_back(t.row(), t.col(), 1.0);
  for (int k = 0; k < m; ++k) {
    for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e)
      if (inverseMass[entryParticle_[e]] != 0.0)
        for (int r = 0; r < 2; ++r) pattern.emplace_back(dofs + k, 2 * entryParticle_[e] + r, 1.0);
    pattern.emplace_back(dofs + k, dofs + k, 1.0);
    // Geometric stiffness couples every pair of free particles of the constraint.
    for (int eb = rowStart_[k]; eb < rowStart_[k + 1]; ++eb)
      for (int ea = rowStart_[k]; ea < rowStart_[k + 1]; ++ea)
        for (int c = 0; c < 2; ++c)
          for (int r = 0; r < 2; ++r) {
            const int row = 2 * entryParticle_[ea] + r, col = 2 * entryParticle_[eb] + c;
            if (free(row) && free(col)) pattern.emplace_back(row, col, 1.0);
          }
  }
  const int size = dofs + m;
  order_.resize(size);
  if (direct) {
    const std::size_t oneSided = pattern.size();
    for (std::size_t i = 0; i < oneSided; ++i)
      pattern.emplace_back(pattern[i].col(), pattern[i].row(), 1.0);
    SparseMatrix symmetric(size, size);
    symmetric.setFromTriplets(pattern.begin(), pattern.end());
    pattern.resize(oneSided);
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int>()(symmetric, inverse);
    for (int i = 0; i < size; ++i) order_[inverse.indices()[i]] = i;
  } else {
    for (int i = 0; i < size; ++i) order_[i] = i;
  }
  // (r, c) in the original numbering → (row, column) of the stored upper triangle.
  auto upper = [&](int r, int c) {
    const int a = order_[r], b = order_[c];
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  for (auto& t : pattern) {
    const auto rc = upper(t.row(), t.col());
    t = Eigen::Triplet<double>(rc.first, rc.second, 1.0);
  }
  matrix_.resize(size, size);
  matrix_.setFromTriplets(pattern.begin(), pattern.end());
  matrix_.makeCompressed();

  auto slot = [&](int r, int c) {
    const auto rc = upper(r, c);
    const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[rc.second];
    const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[rc.second + 1];
    return static_cast<int>(std::lower_bound(begin, end, rc.first) - matrix_.innerIndexPtr());
  };
  diagonalSlot_.resize(dofs);
  for (int d = 0; d < dofs; ++d) diagonalSlot_[d] = slot(d, d);
  auto record = [&](const Triplets& list, std::vector<int>& rows, std::vector<int>& cols,
                    std::vector<int>& slots) {
    rows.resize(list.size());
    cols.resize(list.size());
    slots.resize(list.size());
    for (std::size_t k = 0; k < list.size(); ++k) {
      rows[k] = list[k].row();
      cols[k] = list[k].col();
      slots[k] = free(rows[k]) && free(cols[k]) ? slot(rows[k], cols[k]) : -1;
    }
  };
  record(dfdx_, xRow_, xCol_, xSlot_);
  record(dfdv_, vRow_, vCol_, vSlot_);
  jSlot_.assign(2 * J_.size(), -1);
  complianceSlot_.resize(m);
  for (int k = 0; k < m; ++k) {
    for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e)
      if (inverseMass[entryParticle_[e]] != 0.0)
        for (int r = 0; r < 2; ++r) jSlot_[2 * e + r] = slot(dofs + k, 2 * entryParticle_[e] + r);
    complianceSlot_[k] = slot(dofs + k, dofs + k);
  }
  // In the loop order of addGeometricStiffness: k, then column (b, c), then row (a, r).
  gSlot_.clear();
  for (int k = 0; k < m; ++k)
    for (int eb = rowStart_[k]; eb < rowStart_[k + 1]; ++eb)
      for (int c = 0; c < 2; ++c)
        for (int ea = rowStart_[k]; ea < rowStart_[k + 1]; ++ea)
          for (int r = 0; r < 2; ++r) {
            const int row = 2 * entryParticle_[ea] + r, col = 2 * entryParticle_[eb] + c;
            gSlot_.push_back(free(row) && free(col) ? slot(row, col) : -1);
          }

  cachedPinned_.resize(n);
  for (int i = 0; i < n; ++i) cachedPinned_[i] = inverseMass[i] == 0.0;
  cachedWithConstraints_ = withConstraints;
  cachedDirect_ = direct;
  cachedRowStart_ = withConstraints ? rowStart_ : std::vector<int>{};
  cachedEntryParticle_ = withConstraints ? entryParticle_ : std::vector<int>{};
  ldltAnalysed_ = false;  // analysed on first use, by whichever solver is chosen
  analysed_ = true;
}

// Values of the stored KKT triangle. A triplet (r, c, a) of K or D lands in the
// slot of (r, c) — shared with (c, r) — with weight ½ off the diagonal, so the matrix is the
// symmetric part of what the forces report (the definite Jacobians already are).
// With Kv given, K v₀ is summed in the same pass. Returns false, having written
// only part of the values, when a triplet is not where the pattern has it.
bool ImplicitEulerIntegrator::fillValues(int n, double h, const Eigen::VectorXd& mass,
                                         const Eigen::VectorXd& inverseMass, bool withConstraints,
                                         Eigen::VectorXd* Kv) {
  double* value = matrix_.valuePtr();
  std::fill(value, value + matrix_.nonZeros(), 0.0);
  for (int d = 0; d < 2 * n; ++d)
    value[diagonalSlot_[d]] = inverseMass[d / 2] == 0.0 ? 1.0 : mass[d / 2];
  const double hx = -h * h, hv = -h;
  for (std::size_t k = 0; k < dfdx_.size(); ++k) {
    const Eigen::Triplet<double>& t = dfdx_[k];
    if (t.row() != xRow_[k] || t.col() != xCol_[k]) return false;
    if (Kv) (*Kv)[t.row()] += t.value() * v0_[t.col()];
    if (xSlot_[k] >= 0) value[xSlot_[k]] += (t.row() == t.col() ? hx : 0.5 * hx) * t.value();
  }
  for (std::size_t k = 0; k < dfdv_.size(); ++k) {
    const Eigen::Triplet<double>& t = dfdv_[k];
    if (t.row() != vRow_[k] || t.col() != vCol_[k]) return false;
    if (vSlot_[k] >= 0) value[vSlot_[k]] += (t.row() == t.col() ? hv : 0.5 * hv) * t.value();
  }
  if (!withConstraints) return true;
  const int m = static_cast<int>(rowStart_.size()) - 1;
  for (int k = 0; k < m; ++k) {
    double diagonal = 0.0;  // row k of diag(J W Jᵀ)
    for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e) {
      const double w = inverseMass[entryParticle_[e]];
      if (w == 0.0) continue;
      diagonal += w * J_[e].squaredNorm();
      for (int r = 0; r < 2; ++r) value[jSlot_[2 * e + r]] = J_[e][r];
    }
    // A row with nothing free (all pinned, or a degenerate J) becomes −ν = 0.
    value[complianceSlot_[k]] = diagonal > 0.0 ? -settings.compliance * diagonal : -1.0;
  }
  return true;
}

// Adds G = h Σ_k max(ν_k, 0) ∂²C_k/∂q² at x to the matrix. The Hessian of C_k
// is read column by column through the constraint interface: J̇ = (∂J/∂q) q̇ is
// linear in q̇, so J̇ at a unit velocity e_j is column j of ∂²C_k/∂q².
void ImplicitEulerIntegrator::addGeometricStiffness(ParticleSystem& system, const Eigen::VectorXd& x,
                                                    double h) {
  const ConstraintList& constraints = system.constraints();
  const Eigen::VectorXd& w = system.inverseMasses();
  double* value = matrix_.valuePtr();
  probe_.setZero(x.size());
  std::size_t g = 0;
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    const std::vector<int>& ps = constraints[k]->particles();
    const std::size_t count = ps.size();
    const double tension = static_cast<Eigen::Index>(k) < nuOld_.size() ? std::max(nuOld_[k], 0.0) : 0.0;
    if (probeJ_.size() < count) probeJ_.resize(count), probeJdot_.resize(count);
    ConstraintRow row;
    row.J = probeJ_.data();
    row.Jdot = probeJdot_.data();
    for (std::size_t b = 0; b < count; ++b)
      for (int c = 0; c < 2; ++c) {
        if (tension > 0.0 && w[ps[b]] != 0.0) {
          probe_[2 * ps[b] + c] = 1.0;
          constraints[k]->evaluate(system.phase(x, probe_), row);
          probe_[2 * ps[b] + c] = 0.0;
        }
        for (std::size_t a = 0; a < count; ++a)
          for (int r = 0; r < 2; ++r, ++g) {
            if (tension == 0.0 || gSlot_[g] < 0) continue;
            const bool diagonal = a == b && r == c;
            value[gSlot_[g]] += (diagonal ? h : 0.5 * h) * tension * probeJdot_[a][r];
          }
      }
  }
}

// out += G dv = h Σ_k max(ν_k, 0) ∂²C_k/∂q² dv, read as J̇ at velocity dv.
void ImplicitEulerIntegrator::addGeometricStiffnessTimes(ParticleSystem& system,
                                                         const Eigen::VectorXd& x,
                                                         const Eigen::VectorXd& dv, double h,
                                                         Eigen::VectorXd& out) {
  const ConstraintList& constraints = system.constraints();
  const Eigen::VectorXd& w = system.inverseMasses();
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    const double tension = static_cast<Eigen::Index>(k) < nuOld_.size() ? std::max(nuOld_[k], 0.0) : 0.0;
    if (tension == 0.0) continue;
    const std::vector<int>& ps = constraints[k]->particles();
    if (probeJ_.size() < ps.size()) probeJ_.resize(ps.size()), probeJdot_.resize(ps.size());
    ConstraintRow row;
    row.J = probeJ_.data();
    row.Jdot = probeJdot_.data();
    constraints[k]->evaluate(system.phase(x, dv), row);
    for (std::size_t a = 0; a < ps.size(); ++a)
      if (w[ps[a]] != 0.0) out.segment<2>(2 * ps[a]) += h * tension * probeJdot_[a];
  }
}

// Jacobi-preconditioned CG on the stored (symmetric, upper) A, from the guess
// in solution_ (the last step's Δv), with scratch kept between steps (Eigen's ConjugateGradient
// allocates four vectors per solve). Pinned rows are the identity with a zero
// right-hand side, so they stay 0.
void ImplicitEulerIntegrator::jacobiConjugateGradient(const Eigen::VectorXd& b) {
  Eigen::VectorXd& x = solution_;
  const Eigen::Index size = b.size();
  inverseDiagonal_.resize(size);
  for (Eigen::Index i = 0; i < size; ++i) {  // CG runs unconstrained and unpermuted: i is a DOF
    const double d = matrix_.valuePtr()[diagonalSlot_[i]];
    inverseDiagonal_[i] = d > 0.0 ? 1.0 / d : 1.0;
  }
  const double bNorm = b.norm();
  iterations_ = 0;
  cgResidual_ = 0.0;
  if (bNorm == 0.0) {
    x.setZero(size);
    return;
  }
  cgAp_.noalias() = matrix_.selfadjointView<Eigen::Upper>() * x;
  cgR_ = b - cgAp_;
  cgZ_ = inverseDiagonal_.cwiseProduct(cgR_);
  cgP_ = cgZ_;
  double rz = cgR_.dot(cgZ_);
  const double target = settings.cgTolerance * bNorm;
  while (iterations_ < settings.cgMaxIterations && cgR_.norm() > target) {
    cgAp_.noalias() = matrix_.selfadjointView<Eigen::Upper>() * cgP_;
    const double alpha = rz / cgP_.dot(cgAp_);
    x += alpha * cgP_;
    cgR_ -= alpha * cgAp_;
    cgZ_ = inverseDiagonal_.cwiseProduct(cgR_);
    const double rzNext = cgR_.dot(cgZ_);
    cgP_ = cgZ_ + (rzNext / rz) * cgP_;
    rz = rzNext;
    ++iterations_;
  }
  cgResidual_ = cgR_.norm() / bNorm;
}

StepStats ImplicitEulerIntegrator::step(ParticleSystem& system, double h) {
  settings.validate();
  requireJacobians(system);
  Eigen::VectorXd& x = system.positions();
  Eigen::VectorXd& v = system.velocities();
  const Eigen::VectorXd& mass = system.masses();
  const Eigen::VectorXd& w = system.inverseMasses();
  const int n = system.size(), dofs = 2 * n;
  x0_ = x;
  v0_ = v;
  const bool coupled = settings.coupledConstraints && !system.constraints().empty();
  const int m = coupled ? static_cast<int>(system.constraints().size()) : 0;

  // f₀: the forces alone when the constraints are in the solve, forces plus
  // the explicit constraint forces Jᵀλ when they are lagged.
  const Phase s = system.phase(x0_, v0_);
  if (!coupled && !system.constraints().empty()) {
    system.acceleration(x0_, v0_, a_);
    f0_ = system.forces();
  } else {
    f0_.setZero(dofs);
    for (const auto& force : system.forceObjects()) force->apply(s, f0_);
  }
  // The lagged scheme's explicit solve, or nothing, from the tally; then this
  // scheme's own force evaluation and solves.
  StepStats stats = system.takeEvaluationStats();
  if (!(!coupled && !system.constraints().empty())) ++stats.forceEvaluations;
  dfdx_.clear();
  dfdv_.clear();
  for (const auto& force : system.forceObjects()) force->addDefiniteJacobians(s, dfdx_, dfdv_);
  if (coupled) gatherConstraints(system, x0_, v0_);
  usedDirect_ = coupled || settings.solver == ImplicitLinearSolver::Direct;
  if (!patternMatches(n, w, coupled, usedDirect_)) buildPattern(system, coupled, usedDirect_);
  Kv_.setZero(dofs);
  if (!fillValues(n, h, mass, w, coupled, &Kv_)) {
    buildPattern(system, coupled, usedDirect_);
    Kv_.setZero(dofs);
    fillValues(n, h, mass, w, coupled, &Kv_);
  }

  // Right-hand side h (f₀ + h K v₀) on the free degrees of freedom.
  rhsForces_.resize(dofs);
  for (int d = 0; d < dofs; ++d) rhsForces_[d] = w[d / 2] == 0.0 ? 0.0 : h * (f0_[d] + h * Kv_[d]);
  rhs_.resize(dofs + m);

  iterations_ = 0;
  // The impulses of the last step start the Newton iteration (their tension
  // gives the first pass its geometric stiffness).
  if (nuOld_.size() != m) nuOld_.setZero(m);

  // Newton on the constraints (see the header). Pass 0 starts from Δv = 0,
  // linearised at x₀ with the curvature term; pass p > 0 from the last
  // (Δv, ν), linearised at x̃ = x₀ + h v̄:
  //   [A + G  J̃ᵀ] [Δv]   [r₁ + G Δv_old     ]
  //   [J̃     −E ] [ν ] = [J̃ Δv_old − β C̃/h ]
  const int passes = coupled ? settings.constraintPasses : 1;
  for (passes_ = 0; passes_ < passes; ++passes_) {
    const Eigen::VectorXd* xLin = &x0_;
    if (passes_ > 0) {
      xTrial_ = x0_ + h * vBar_;
      if (worstRelativeViolation(system, xTrial_, vBar_) <= settings.constraintTolerance) break;
      gatherConstraints(system, xTrial_, vBar_);
      xLin = &xTrial_;
    }
    if (passes_ > 0) fillValues(n, h, mass, w, coupled, nullptr);
    if (coupled && settings.geometricStiffness) addGeometricStiffness(system, *xLin, h);
    rhs_.head(dofs) = rhsForces_;
    if (passes_ > 0 && settings.geometricStiffness) {
      dvOld_ = vBar_ - v0_;
      addGeometricStiffnessTimes(system, xTrial_, dvOld_, h, rhs_);  // writes rows < 2n only
    }
    for (int k = 0; k < m; ++k) {
      // Row k: J v⁺ = c, written for the unknown Δv = v⁺ − v₀.
      double jv0 = 0.0, jvbar = 0.0, curvature = 0.0;
      bool anyFree = false;
      for (int e = rowStart_[k]; e < rowStart_[k + 1]; ++e) {
        const int p = entryParticle_[e];
        if (passes_ == 0) curvature += Jdot_[e].dot(v0_.segment<2>(2 * p));
        if (w[p] == 0.0) continue;
        anyFree = true;
        jv0 += J_[e].dot(v0_.segment<2>(2 * p));
        if (passes_ > 0) jvbar += J_[e].dot(vBar_.segment<2>(2 * p));
      }
      const double c = passes_ == 0 ? -settings.stabilization * C_[k] / h - 0.5 * h * curvature
                                    : jvbar - settings.stabilization * C_[k] / h;
      rhs_[dofs + k] = anyFree ? c - jv0 : 0.0;
    }
    // Solve in the stored numbering: unknown i sits at order_[i].
    permutedRhs_.resize(dofs + m);
    for (int i = 0; i < dofs + m; ++i) permutedRhs_[order_[i]] = rhs_[i];
    if (usedDirect_) {
      if (!ldltAnalysed_) {
        ldlt_.analyzePattern(matrix_);
        ldltAnalysed_ = true;
      }
      ldlt_.factorizeInPlace(matrix_);
      ++stats.factorizations;
      // A failed factorisation (only a blown-up, non-finite state gets here:
      // the matrix is quasi-definite) leaves NaN, reported as a failed solve.
      if (ldlt_.info() != Eigen::Success) {
        solution_.setConstant(dofs + m, NAN);
      } else {
        solution_ = ldlt_.solve(permutedRhs_);
        const double bNorm = permutedRhs_.norm();
        cgAp_.noalias() = matrix_.selfadjointView<Eigen::Upper>() * solution_;
        stats.maxResidual = std::max(stats.maxResidual, bNorm > 0.0 ? (permutedRhs_ - cgAp_).norm() / bNorm : 0.0);
      }
    } else {
      // Warm start from the last step's Δv (solution_ still holds it).
      if (solution_.size() != dofs || !solution_.allFinite()) solution_.setZero(dofs);
      jacobiConjugateGradient(permutedRhs_);
      stats.cgIterations += iterations_;
      stats.maxResidual = std::max(stats.maxResidual, cgResidual_);
    }
    ++stats.solves;
    if (!solution_.allFinite()) stats.failure = StepFailure::SolveFailed;
    z_.resize(dofs + m);
    for (int i = 0; i < dofs + m; ++i) z_[i] = solution_[order_[i]];
    vBar_ = v0_ + z_.head(dofs);
    nuOld_ = z_.tail(m);
  }

  v = vBar_;
  x = x0_ + h * v;
  lastStep_ = h;
  return stats;
}

}  // namespace particles

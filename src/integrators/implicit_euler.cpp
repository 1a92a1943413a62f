#include "particles/integrators/implicit_euler.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "particles/check.h"
#include "particles/particle_system.h"

namespace particles {

void ImplicitEulerSettings::validate() const {
  requireInRange("implicit stabilization beta", stabilization, 0.0, 1.0);
  if (constraintPasses < 1)
    throw std::invalid_argument("implicit constraint passes must be >= 1, got " +
                                std::to_string(constraintPasses));
  requirePositive("implicit constraint tolerance", constraintTolerance);
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

// Everything one step needs between its phases, and what is kept from one step
// to the next (the sparsity pattern, the factorisation's analysis, the warm starts).
struct ImplicitEulerIntegrator::Impl {
  using SparseMatrix = Eigen::SparseMatrix<double>;
  const ImplicitEulerSettings* settings = nullptr;

  // --- the step's start and its iterate -----------------------------------
  int n = 0, dofs = 0, m = 0;  // particles, velocity unknowns, constraints in the solve
  bool coupled = false;
  Eigen::VectorXd x0, v0;
  Eigen::VectorXd vBar, nu;     // iterate v̄, ν̄ (ν kept as the next step's warm start)
  Eigen::VectorXd xTilde, xMid; // x̃ = x₀ + h v̄, x_m = x₀ + h v̄/2

  // --- forces at the linearisation point ----------------------------------
  Eigen::VectorXd f;            // f at the iterate (pass 0: f₀ + h K₀ v₀)
  Eigen::VectorXd acceleration; // the lagged scheme's explicit evaluation
  Triplets dfdx, dfdv;

  // --- constraint rows, compressed: entries rowStart[k] .. rowStart[k+1] ---
  std::vector<int> rowStart, entryParticle;
  std::vector<Eigen::Vector2d> J, Jdot, Gbar, scratchJ, scratchJdot;
  Eigen::VectorXd C, C0;        // C(x̃) and C(x₀)
  std::vector<char> fixedRow;   // nothing free in the row (all pinned, or J = 0): ν = 0

  // --- residuals of the iterate --------------------------------------------
  Eigen::VectorXd residual;     // (−R₁, −R₂/h): the right-hand side of a pass
  double constraintResidual = 0.0, momentumResidual = 0.0;
  int passes = 0;

  // --- the linear system (pattern cache, factorisation, CG) ----------------
  std::vector<int> xRow, xCol, vRow, vCol, xSlot, vSlot;
  std::vector<int> diagonalSlot, jSlot, complianceSlot, gSlot;
  std::vector<int> cachedRowStart, cachedEntryParticle;
  std::vector<char> cachedPinned;
  bool cachedWithConstraints = false, cachedDirect = false, analysed = false;
  SparseMatrix matrix;          // upper triangle of the KKT matrix (or of A), permuted
  Eigen::VectorXi order;        // unknown i is row order[i] of matrix
  // SimplicialLDLT that factorises the stored, already permuted matrix in
  // place (Eigen's factorize() makes a temporary copy, allocating each step).
  struct InPlaceLdlt : Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>> {
    void factorizeInPlace(const SparseMatrix& upper) { this->template factorize_preordered<true>(upper); }
  };
  InPlaceLdlt ldlt;
  bool ldltAnalysed = false, usedDirect = true;
  Eigen::VectorXd permutedRhs, solution, increment, inverseDiagonal, cgR, cgZ, cgP, cgAp, probe;
  int cgIterations = 0;
  double cgResidual = 0.0;

  // Phases of the step.
  void begin(ParticleSystem& system);
  StepStats lineariseForcesAtStart(ParticleSystem& system, double h);
  void evaluateForces(ParticleSystem& system, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  void lineariseForces(ParticleSystem& system, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  void gatherConstraintRows(ParticleSystem& system, double h);
  void measureResiduals(ParticleSystem& system, double h);
  bool converged() const;
  void assemble(ParticleSystem& system, double h);
  void solvePass(double h, StepStats& stats);
  void commit(ParticleSystem& system, double h) const;

  // Pieces of assemble() and solvePass().
  void evaluateRows(ParticleSystem& system, const Eigen::VectorXd& x, std::vector<Eigen::Vector2d>& rowsJ,
                    Eigen::VectorXd* values);
  bool patternMatches(const Eigen::VectorXd& inverseMass, bool direct) const;
  void buildPattern(const Eigen::VectorXd& inverseMass, bool direct);
  bool fillValues(double h, const Eigen::VectorXd& mass, const Eigen::VectorXd& inverseMass);
  void addGeometricStiffness(ParticleSystem& system, double h);
  void jacobiConjugateGradient(const Eigen::VectorXd& b);
};

ImplicitEulerIntegrator::ImplicitEulerIntegrator() : impl_(std::make_unique<Impl>()) {}
ImplicitEulerIntegrator::~ImplicitEulerIntegrator() = default;
int ImplicitEulerIntegrator::lastPasses() const { return impl_->passes; }
double ImplicitEulerIntegrator::lastConstraintResidual() const { return impl_->constraintResidual; }
double ImplicitEulerIntegrator::lastMomentumResidual() const { return impl_->momentumResidual; }

StepStats ImplicitEulerIntegrator::step(ParticleSystem& system, double h) {
  settings.validate();
  requireJacobians(system);
  Impl& s = *impl_;
  s.settings = &settings;
  s.begin(system);
  StepStats stats = s.lineariseForcesAtStart(system, h);
  const int maxPasses = s.coupled ? settings.constraintPasses : 1;
  for (s.passes = 0;; ++s.passes) {
    if (s.coupled) {
      s.gatherConstraintRows(system, h);
      if (s.passes > 0) {
        s.evaluateForces(system, s.xTilde, s.vBar);
        ++stats.forceEvaluations;
      }
      s.measureResiduals(system, h);
      if (s.passes > 0 && s.converged()) break;
    } else {
      s.measureResiduals(system, h);
    }
    if (s.passes == maxPasses) break;
    if (s.passes > 0) s.lineariseForces(system, s.xTilde, s.vBar);
    s.assemble(system, h);
    s.solvePass(h, stats);
    if (stats.failure != StepFailure::None) break;
    if (!s.coupled) {  // one linearly implicit pass: nothing left to measure
      s.passes = 1;
      break;
    }
  }
  s.commit(system, h);
  lastStep_ = h;
  return stats;
}

// --- phases ----------------------------------------------------------------

void ImplicitEulerIntegrator::Impl::begin(ParticleSystem& system) {
  n = system.size();
  dofs = 2 * n;
  coupled = settings->coupledConstraints && !system.constraints().empty();
  m = coupled ? static_cast<int>(system.constraints().size()) : 0;
  x0 = system.positions();
  v0 = system.velocities();
  vBar = v0;
  // The last step's impulses start the iteration (their tension gives the first
  // pass its geometric stiffness).
  if (nu.size() != m) nu.setZero(m);
  constraintResidual = momentumResidual = 0.0;
  if (!coupled) return;

  const ConstraintList& constraints = system.constraints();
  rowStart.resize(m + 1);
  rowStart[0] = 0;
  for (int k = 0; k < m; ++k)
    rowStart[k + 1] = rowStart[k] + static_cast<int>(constraints[k]->particles().size());
  entryParticle.resize(rowStart[m]);
  for (int k = 0; k < m; ++k)
    for (int e = rowStart[k], i = 0; e < rowStart[k + 1]; ++e, ++i) entryParticle[e] = constraints[k]->particles()[i];
  J.resize(rowStart[m]);
  Jdot.resize(rowStart[m]);
  Gbar.resize(rowStart[m]);
  C0.resize(m);
  evaluateRows(system, x0, scratchJ, &C0);
}

// f₀ and its Jacobians at the start state; f then holds Baraff & Witkin's
// f(x₀ + h v₀, v₀) ≈ f₀ + h K₀ v₀ for the first iterate. With lagged
// constraints, f₀ includes the explicit solve's constraint forces.
StepStats ImplicitEulerIntegrator::Impl::lineariseForcesAtStart(ParticleSystem& system, double h) {
  const bool lagged = !settings->coupledConstraints && !system.constraints().empty();
  if (lagged) {
    system.acceleration(x0, v0, acceleration);
    f = system.forces();
  }
  // The lagged scheme's explicit solve, or nothing, from the tally; then this
  // scheme's own evaluation.
  StepStats stats = system.takeEvaluationStats();
  if (!lagged) {
    evaluateForces(system, x0, v0);
    ++stats.forceEvaluations;
  }
  lineariseForces(system, x0, v0);
  for (const auto& t : dfdx) f[t.row()] += h * t.value() * v0[t.col()];
  return stats;
}

void ImplicitEulerIntegrator::Impl::evaluateForces(ParticleSystem& system, const Eigen::VectorXd& x,
                                                   const Eigen::VectorXd& v) {
  const Phase phase = system.phase(x, v);
  f.setZero(dofs);
  for (const auto& force : system.forceObjects()) force->apply(phase, f);
}

void ImplicitEulerIntegrator::Impl::lineariseForces(ParticleSystem& system, const Eigen::VectorXd& x,
                                                    const Eigen::VectorXd& v) {
  const Phase phase = system.phase(x, v);
  dfdx.clear();
  dfdv.clear();
  for (const auto& force : system.forceObjects()) force->addDefiniteJacobians(phase, dfdx, dfdv);
}

// C and J at x (J̇ at x's velocity is not needed and is written to scratch).
void ImplicitEulerIntegrator::Impl::evaluateRows(ParticleSystem& system, const Eigen::VectorXd& x,
                                                 std::vector<Eigen::Vector2d>& rowsJ, Eigen::VectorXd* values) {
  const ConstraintList& constraints = system.constraints();
  const Phase phase = system.phase(x, v0);
  rowsJ.resize(rowStart[m]);
  scratchJdot.resize(rowStart[m]);
  for (int k = 0; k < m; ++k) {
    ConstraintRow row;
    row.J = &rowsJ[rowStart[k]];
    row.Jdot = &scratchJdot[rowStart[k]];
    constraints[k]->evaluate(phase, row);
    if (values) (*values)[k] = row.C;
  }
}

// At the iterate: C̃ = C(x̃) and J̃ = J(x̃) for the Newton matrix, and the
// discrete gradient Ḡ between x₀ and x̃ (header) along which the impulses act.
void ImplicitEulerIntegrator::Impl::gatherConstraintRows(ParticleSystem& system, double h) {
  const Eigen::VectorXd& w = system.inverseMasses();
  const ConstraintList& constraints = system.constraints();
  xTilde = x0 + h * vBar;
  xMid = x0 + (0.5 * h) * vBar;
  C.resize(m);
  evaluateRows(system, xTilde, J, &C);
  evaluateRows(system, xMid, Gbar, nullptr);  // J(x_m), corrected below
  fixedRow.assign(m, 0);
  for (int k = 0; k < m; ++k) {
    double jjFree = 0.0, dxSquared = 0.0, predicted = 0.0;
    for (int e = rowStart[k]; e < rowStart[k + 1]; ++e) {
      const int p = entryParticle[e];
      const Eigen::Vector2d dx = xTilde.segment<2>(2 * p) - x0.segment<2>(2 * p);
      dxSquared += dx.squaredNorm();
      predicted += Gbar[e].dot(dx);
      if (w[p] != 0.0) jjFree += J[e].squaredNorm();
    }
    fixedRow[k] = jjFree == 0.0;
    // Gonzalez's correction makes Ḡ Δx = C(x̃) − C(x₀) exactly. It is O(|Δx|²)
    // and zero for quadratic C; below a relative step of 1e-6 it would be
    // rounding divided by |Δx|² and is left out (its effect is then O(|Δx|³)).
    const double scale = constraints[k]->lengthScale() > 0.0 ? constraints[k]->lengthScale() : 1.0;
    if (dxSquared > 1e-12 * scale * scale) {
      const double correction = (C[k] - C0[k] - predicted) / dxSquared;
      for (int e = rowStart[k]; e < rowStart[k + 1]; ++e) {
        const int p = entryParticle[e];
        Gbar[e] += correction * (xTilde.segment<2>(2 * p) - x0.segment<2>(2 * p));
      }
    }
    if (fixedRow[k]) nu[k] = 0.0;
  }
}

// residual = (−R₁, −R₂/h) at the iterate, and the two relative measures of the
// stopping test (header).
void ImplicitEulerIntegrator::Impl::measureResiduals(ParticleSystem& system, double h) {
  const Eigen::VectorXd& mass = system.masses();
  const Eigen::VectorXd& w = system.inverseMasses();
  const double beta = settings->stabilization;
  residual.setZero(dofs + m);
  Eigen::Ref<Eigen::VectorXd> r1 = residual.head(dofs);
  for (int d = 0; d < dofs; ++d)
    if (w[d / 2] != 0.0) r1[d] = h * f[d] - mass[d / 2] * (vBar[d] - v0[d]);
  constraintResidual = 0.0;
  double velocityScale = 0.0;
  for (int k = 0; k < m; ++k) {
    if (fixedRow[k]) continue;
    double jj = 0.0;
    for (int e = rowStart[k]; e < rowStart[k + 1]; ++e) {
      const int p = entryParticle[e];
      if (w[p] == 0.0) continue;
      r1.segment<2>(2 * p) -= nu[k] * Gbar[e];
      jj += J[e].squaredNorm();
    }
    const double r2 = C[k] - (1.0 - beta) * C0[k];
    residual[dofs + k] = -r2 / h;
    const double scale = system.constraints()[k]->lengthScale() > 0.0 ? system.constraints()[k]->lengthScale() : 1.0;
    constraintResidual = std::max(constraintResidual, std::abs(r2) / (std::sqrt(jj) * scale));
  }
  if (!coupled) return;
  // Velocity scale of R₁/m: the sizes of the terms it balances, |v̄|, h|W f|, |W Ḡᵀν̄|.
  double worst = 0.0;
  for (int d = 0; d < dofs; ++d) {
    const double wd = w[d / 2];
    if (wd == 0.0) continue;
    const double impulse = mass[d / 2] * (vBar[d] - v0[d]) - h * f[d] + r1[d];  // −(Ḡᵀν̄)_d
    velocityScale = std::max(velocityScale, std::abs(vBar[d]) + h * wd * std::abs(f[d]) + wd * std::abs(impulse));
    worst = std::max(worst, wd * std::abs(r1[d]));
  }
  momentumResidual = velocityScale > 0.0 ? worst / velocityScale : 0.0;
}

bool ImplicitEulerIntegrator::Impl::converged() const {
  return constraintResidual <= settings->constraintTolerance && momentumResidual <= settings->constraintTolerance;
}

// The values of the pass's matrix, in the cached pattern (rebuilt when the
// structure changed).
void ImplicitEulerIntegrator::Impl::assemble(ParticleSystem& system, double h) {
  const Eigen::VectorXd& w = system.inverseMasses();
  usedDirect = coupled || settings->solver == ImplicitLinearSolver::Direct;
  if (!patternMatches(w, usedDirect)) buildPattern(w, usedDirect);
  if (!fillValues(h, system.masses(), w)) {
    buildPattern(w, usedDirect);
    fillValues(h, system.masses(), w);
  }
  if (coupled && settings->geometricStiffness) addGeometricStiffness(system, h);
}

// One Newton solve for (δv, δν), then the iterate moves: v̄ += δv, ν̄ += δν.
void ImplicitEulerIntegrator::Impl::solvePass(double h, StepStats& stats) {
  (void)h;
  const int size = dofs + m;
  permutedRhs.resize(size);
  for (int i = 0; i < size; ++i) permutedRhs[order[i]] = residual[i];
  if (usedDirect) {
    if (!ldltAnalysed) {
      ldlt.analyzePattern(matrix);
      ldltAnalysed = true;
    }
    ldlt.factorizeInPlace(matrix);
    ++stats.factorizations;
    // A failed factorisation (only a blown-up, non-finite state gets here:
    // the matrix is quasi-definite) leaves NaN, reported as a failed solve.
    if (ldlt.info() != Eigen::Success) {
      solution.setConstant(size, NAN);
    } else {
      solution = ldlt.solve(permutedRhs);
      const double bNorm = permutedRhs.norm();
      cgAp.noalias() = matrix.selfadjointView<Eigen::Upper>() * solution;
      stats.maxResidual = std::max(stats.maxResidual, bNorm > 0.0 ? (permutedRhs - cgAp).norm() / bNorm : 0.0);
    }
  } else {
    // Warm start from the last step's Δv (solution still holds it).
    if (solution.size() != dofs || !solution.allFinite()) solution.setZero(dofs);
    jacobiConjugateGradient(permutedRhs);
    stats.cgIterations += cgIterations;
    stats.maxResidual = std::max(stats.maxResidual, cgResidual);
  }
  ++stats.solves;
  if (!solution.allFinite()) {
    stats.failure = StepFailure::SolveFailed;
    return;
  }
  increment.resize(size);
  for (int i = 0; i < size; ++i) increment[i] = solution[order[i]];
  vBar += increment.head(dofs);
  for (int k = 0; k < m; ++k)
    if (!fixedRow[k]) nu[k] += increment[dofs + k];
}

void ImplicitEulerIntegrator::Impl::commit(ParticleSystem& system, double h) const {
  if (!vBar.allFinite()) return;  // a failed solve leaves the start state
  system.velocities() = vBar;
  system.positions() = x0 + h * vBar;
}

// --- the linear system -------------------------------------------------------

bool ImplicitEulerIntegrator::Impl::patternMatches(const Eigen::VectorXd& inverseMass, bool direct) const {
  if (!analysed || coupled != cachedWithConstraints || direct != cachedDirect) return false;
  if (static_cast<int>(cachedPinned.size()) != n) return false;
  for (int i = 0; i < n; ++i)
    if (cachedPinned[i] != (inverseMass[i] == 0.0)) return false;
  // Each triplet's position is checked while fillValues() scatters it.
  if (dfdx.size() != xRow.size() || dfdv.size() != vRow.size()) return false;
  if (coupled && (rowStart != cachedRowStart || entryParticle != cachedEntryParticle)) return false;
  return true;
}

// The KKT matrix: A on the 2n velocity unknowns, then one row per constraint,
// stored as the upper triangle in a permuted numbering (unknown i at order[i]):
// an AMD fill-reducing order for the direct solve, so that the LDLᵀ
// factorises the stored matrix in place without a per-step permuted copy, and
// the identity for CG, whose products are faster in the mesh's own order.
// Every value's destination in matrix.valuePtr() is recorded so that
// fillValues() is a scatter, with no search and no allocation.
void ImplicitEulerIntegrator::Impl::buildPattern(const Eigen::VectorXd& inverseMass, bool direct) {
  auto free = [&](int dof) { return inverseMass[dof / 2] != 0.0; };

  // Every (row, column) of the symmetric matrix, in the original numbering.
  Triplets pattern;
  pattern.reserve(dofs + dfdx.size() + dfdv.size() + 2 * J.size() + m);
  for (int d = 0; d < dofs; ++d) pattern.emplace_back(d, d, 1.0);
  for (const Triplets* list : {&dfdx, &dfdv})
    for (const auto& t : *list)
      if (free(t.row()) && free(t.col())) pattern.emplace_back(t.row(), t.col(), 1.0);
  for (int k = 0; k < m; ++k) {
    for (int e = rowStart[k]; e < rowStart[k + 1]; ++e)
      if (inverseMass[entryParticle[e]] != 0.0)
        for (int r = 0; r < 2; ++r) pattern.emplace_back(dofs + k, 2 * entryParticle[e] + r, 1.0);
    pattern.emplace_back(dofs + k, dofs + k, 1.0);
    // Geometric stiffness couples every pair of free particles of the constraint.
    for (int eb = rowStart[k]; eb < rowStart[k + 1]; ++eb)
      for (int ea = rowStart[k]; ea < rowStart[k + 1]; ++ea)
        for (int c = 0; c < 2; ++c)
          for (int r = 0; r < 2; ++r) {
            const int row = 2 * entryParticle[ea] + r, col = 2 * entryParticle[eb] + c;
            if (free(row) && free(col)) pattern.emplace_back(row, col, 1.0);
          }
  }
  const int size = dofs + m;
  order.resize(size);
  if (direct) {
    const std::size_t oneSided = pattern.size();
    for (std::size_t i = 0; i < oneSided; ++i) pattern.emplace_back(pattern[i].col(), pattern[i].row(), 1.0);
    SparseMatrix symmetric(size, size);
    symmetric.setFromTriplets(pattern.begin(), pattern.end());
    pattern.resize(oneSided);
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int>()(symmetric, inverse);
    for (int i = 0; i < size; ++i) order[inverse.indices()[i]] = i;
  } else {
    for (int i = 0; i < size; ++i) order[i] = i;
  }
  // (r, c) in the original numbering → (row, column) of the stored upper triangle.
  auto upper = [&](int r, int c) {
    const int a = order[r], b = order[c];
    return std::make_pair(std::min(a, b), std::max(a, b));
  };
  for (auto& t : pattern) {
    const auto rc = upper(t.row(), t.col());
    t = Eigen::Triplet<double>(rc.first, rc.second, 1.0);
  }
  matrix.resize(size, size);
  matrix.setFromTriplets(pattern.begin(), pattern.end());
  matrix.makeCompressed();

  auto slot = [&](int r, int c) {
    const auto rc = upper(r, c);
    const int* begin = matrix.innerIndexPtr() + matrix.outerIndexPtr()[rc.second];
    const int* end = matrix.innerIndexPtr() + matrix.outerIndexPtr()[rc.second + 1];
    return static_cast<int>(std::lower_bound(begin, end, rc.first) - matrix.innerIndexPtr());
  };
  diagonalSlot.resize(dofs);
  for (int d = 0; d < dofs; ++d) diagonalSlot[d] = slot(d, d);
  auto record = [&](const Triplets& list, std::vector<int>& rows, std::vector<int>& cols, std::vector<int>& slots) {
    rows.resize(list.size());
    cols.resize(list.size());
    slots.resize(list.size());
    for (std::size_t k = 0; k < list.size(); ++k) {
      rows[k] = list[k].row();
      cols[k] = list[k].col();
      slots[k] = free(rows[k]) && free(cols[k]) ? slot(rows[k], cols[k]) : -1;
    }
  };
  record(dfdx, xRow, xCol, xSlot);
  record(dfdv, vRow, vCol, vSlot);
  jSlot.assign(2 * (coupled ? J.size() : 0), -1);
  complianceSlot.resize(m);
  for (int k = 0; k < m; ++k) {
    for (int e = rowStart[k]; e < rowStart[k + 1]; ++e)
      if (inverseMass[entryParticle[e]] != 0.0)
        for (int r = 0; r < 2; ++r) jSlot[2 * e + r] = slot(dofs + k, 2 * entryParticle[e] + r);
    complianceSlot[k] = slot(dofs + k, dofs + k);
  }
  // In the loop order of addGeometricStiffness: k, then column (b, c), then row (a, r).
  gSlot.clear();
  for (int k = 0; k < m; ++k)
    for (int eb = rowStart[k]; eb < rowStart[k + 1]; ++eb)
      for (int c = 0; c < 2; ++c)
        for (int ea = rowStart[k]; ea < rowStart[k + 1]; ++ea)
          for (int r = 0; r < 2; ++r) {
            const int row = 2 * entryParticle[ea] + r, col = 2 * entryParticle[eb] + c;
            gSlot.push_back(free(row) && free(col) ? slot(row, col) : -1);
          }

  cachedPinned.resize(n);
  for (int i = 0; i < n; ++i) cachedPinned[i] = inverseMass[i] == 0.0;
  cachedWithConstraints = coupled;
  cachedDirect = direct;
  cachedRowStart = coupled ? rowStart : std::vector<int>{};
  cachedEntryParticle = coupled ? entryParticle : std::vector<int>{};
  ldltAnalysed = false;  // analysed on first use
  analysed = true;
}

// Values of the stored KKT triangle: A = M − h D − h² K, J̃ and −E. A triplet
// (r, c, a) of K or D lands in the slot of (r, c) — shared with (c, r) — with
// weight ½ off the diagonal, so the matrix is the symmetric part of what the
// forces report (the definite Jacobians already are). Returns false, having
// written only part of the values, when a triplet is not where the pattern has it.
bool ImplicitEulerIntegrator::Impl::fillValues(double h, const Eigen::VectorXd& mass,
                                               const Eigen::VectorXd& inverseMass) {
  double* value = matrix.valuePtr();
  std::fill(value, value + matrix.nonZeros(), 0.0);
  for (int d = 0; d < dofs; ++d) value[diagonalSlot[d]] = inverseMass[d / 2] == 0.0 ? 1.0 : mass[d / 2];
  const double hx = -h * h, hv = -h;
  for (std::size_t k = 0; k < dfdx.size(); ++k) {
    const Eigen::Triplet<double>& t = dfdx[k];
    if (t.row() != xRow[k] || t.col() != xCol[k]) return false;
    if (xSlot[k] >= 0) value[xSlot[k]] += (t.row() == t.col() ? hx : 0.5 * hx) * t.value();
  }
  for (std::size_t k = 0; k < dfdv.size(); ++k) {
    const Eigen::Triplet<double>& t = dfdv[k];
    if (t.row() != vRow[k] || t.col() != vCol[k]) return false;
    if (vSlot[k] >= 0) value[vSlot[k]] += (t.row() == t.col() ? hv : 0.5 * hv) * t.value();
  }
  for (int k = 0; k < m; ++k) {
    double diagonal = 0.0;  // row k of diag(J̃ W J̃ᵀ)
    for (int e = rowStart[k]; e < rowStart[k + 1]; ++e) {
      const double w = inverseMass[entryParticle[e]];
      if (w == 0.0) continue;
      diagonal += w * J[e].squaredNorm();
      for (int r = 0; r < 2; ++r) value[jSlot[2 * e + r]] = fixedRow[k] ? 0.0 : J[e][r];
    }
    // A fixed row (nothing free) becomes −δν = 0.
    value[complianceSlot[k]] = fixedRow[k] || diagonal == 0.0 ? -1.0 : -settings->compliance * diagonal;
  }
  return true;
}

// Adds G = (h/2) Σ_k max(ν̄_k, 0) ∇²C_k(x_m), the derivative of Ḡᵀν̄ with
// respect to v (Ḡ = J(x₀ + h v/2) for quadratic C). The Hessian of C_k is read
// column by column through the constraint interface: J̇ = (∂J/∂q) q̇ is linear
// in q̇, so J̇ at a unit velocity e_j is column j of ∇²C_k.
void ImplicitEulerIntegrator::Impl::addGeometricStiffness(ParticleSystem& system, double h) {
  const ConstraintList& constraints = system.constraints();
  const Eigen::VectorXd& w = system.inverseMasses();
  double* value = matrix.valuePtr();
  const double weight = 0.5 * h;
  probe.setZero(dofs);
  std::size_t g = 0;
  for (int k = 0; k < m; ++k) {
    const std::vector<int>& ps = constraints[k]->particles();
    const std::size_t count = ps.size();
    const double tension = fixedRow[k] ? 0.0 : std::max(nu[k], 0.0);
    if (scratchJ.size() < count) scratchJ.resize(count), scratchJdot.resize(count);
    ConstraintRow row;
    row.J = scratchJ.data();
    row.Jdot = scratchJdot.data();
    for (std::size_t b = 0; b < count; ++b)
      for (int c = 0; c < 2; ++c) {
        if (tension > 0.0 && w[ps[b]] != 0.0) {
          probe[2 * ps[b] + c] = 1.0;
          constraints[k]->evaluate(system.phase(xMid, probe), row);
          probe[2 * ps[b] + c] = 0.0;
        }
        for (std::size_t a = 0; a < count; ++a)
          for (int r = 0; r < 2; ++r, ++g) {
            if (tension == 0.0 || gSlot[g] < 0) continue;
            const bool diagonal = a == b && r == c;
            value[gSlot[g]] += (diagonal ? weight : 0.5 * weight) * tension * scratchJdot[a][r];
          }
      }
  }
}

// Jacobi-preconditioned CG on the stored (symmetric, upper) A, from the guess
// in solution (the last step's Δv), with scratch kept between steps (Eigen's
// ConjugateGradient allocates four vectors per solve). Pinned rows are the
// identity with a zero right-hand side, so they stay 0.
void ImplicitEulerIntegrator::Impl::jacobiConjugateGradient(const Eigen::VectorXd& b) {
  Eigen::VectorXd& x = solution;
  const Eigen::Index size = b.size();
  inverseDiagonal.resize(size);
  for (Eigen::Index i = 0; i < size; ++i) {  // CG runs unconstrained and unpermuted: i is a DOF
    const double d = matrix.valuePtr()[diagonalSlot[i]];
    inverseDiagonal[i] = d > 0.0 ? 1.0 / d : 1.0;
  }
  const double bNorm = b.norm();
  cgIterations = 0;
  cgResidual = 0.0;
  if (bNorm == 0.0) {
    x.setZero(size);
    return;
  }
  cgAp.noalias() = matrix.selfadjointView<Eigen::Upper>() * x;
  cgR = b - cgAp;
  cgZ = inverseDiagonal.cwiseProduct(cgR);
  cgP = cgZ;
  double rz = cgR.dot(cgZ);
  const double target = settings->cgTolerance * bNorm;
  while (cgIterations < settings->cgMaxIterations && cgR.norm() > target) {
    cgAp.noalias() = matrix.selfadjointView<Eigen::Upper>() * cgP;
    const double alpha = rz / cgP.dot(cgAp);
    x += alpha * cgP;
    cgR -= alpha * cgAp;
    cgZ = inverseDiagonal.cwiseProduct(cgR);
    const double rzNext = cgR.dot(cgZ);
    cgP = cgZ + (rzNext / rz) * cgP;
    rz = rzNext;
    ++cgIterations;
  }
  cgResidual = cgR.norm() / bNorm;
}

}  // namespace particles

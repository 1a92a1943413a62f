#include "integrators/implicit_euler.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "linear/linear.h"
#include "particles/check.h"
#include "particles/particle_system.h"

namespace particles {

// Backward Euler with the constraints inside the solve (after Baraff & Witkin,
// "Large Steps in Cloth Simulation", with Newton on the constraints).
//
// The scheme. One step of h from (x₀, v₀) finds v⁺ and the constraint
// impulses ν (ν = −h λ, one per constraint) with x⁺ = x₀ + h v⁺ and
//   R₁ = M (v⁺ − v₀) − h f(x⁺, v⁺) + Ḡᵀ ν = 0          (momentum)
//   R₂ = C(x⁺) − (1 − β) C(x₀)           = 0          (positions; β = 1: C(x⁺) = 0)
// where Ḡ is the discrete gradient of C between x₀ and x⁺ (Gonzalez 1996):
//   Ḡ = J(x_m) + [C(x⁺) − C(x₀) − J(x_m) Δx] Δxᵀ/|Δx|²,  x_m = (x₀ + x⁺)/2,  Δx = x⁺ − x₀,
// so that Ḡ Δx = C(x⁺) − C(x₀) exactly (for the quadratic rods and wires the
// bracket vanishes and Ḡ = J(x_m)).
//
// Why it cannot gain energy. With E = ½ vᵀM v + V(x) and f = −∇V + f_d,
// R₁ = 0 and R₂ = 0 give, exactly,
//   E⁺ − E₀ = −½ |v⁺ − v₀|²_M                        (backward Euler's numerical dissipation)
//             − [∇V(x⁺)·Δx − (V(x⁺) − V(x₀))]          (≥ 0 when V is convex along the step)
//             + h v⁺·f_d(x⁺, v⁺)                       (≤ 0 for drag and spring damping)
//             + β Σ_k ν_k C_k(x₀)/h                     (the constraint impulses' work),
// because v⁺·Ḡᵀν = Σ ν_k (C_k(x⁺) − C_k(x₀))/h. The last term is the only one
// that can be positive, and it is bounded by the violation C(x₀) the previous
// step left, which the Newton passes hold below `constraintTolerance`: the
// impulses do no work on a step that keeps C fixed. (Along J(x⁺), the plain
// backward-Euler direction, they would do (ν/2h) Δxᵀ∇²C Δx of work, which is
// positive for a rod in compression; a Baumgarte feedback k_s C + k_d Ċ or a
// projection after the step adds energy the same way; hence neither is used.)
// Gravity, zero-length springs and drag therefore lose energy on every step,
// at any h, by at least ½|Δv|²_M; a spring under compression has a concave
// transverse potential, whose bracket is then bounded by ½ h² Δv-sized terms
// but not signed.
//
// The step as phases (ImplicitEulerIntegrator::step):
//   linearise forces → gather constraint rows → assemble → Newton passes → commit.
// Each Newton pass is linearised at the current iterate (x̃ = x₀ + h v̄, v̄, ν̄):
//   [A + G   J̃ᵀ] [δv]   [−R₁]     A = M − h D − h² K (D = ∂f/∂v, K = ∂f/∂x at the iterate),
//   [J̃      −E ] [δν] = [−R₂/h],  J̃ = J(x̃),  G = (h/2) Σ max(ν̄_k, 0) ∇²C_k(x_m),
// with E = ε·diag(J̃ W J̃ᵀ) a tiny compliance on the increments (it regularises
// the solve without moving its solution). The first iterate is v̄ = v₀ with
// the last step's impulses; its force and Jacobians are Baraff & Witkin's, taken
// at the start state (f(x₀ + h v₀) ≈ f₀ + h K v₀). Later passes evaluate the
// forces, K, D, C and J at the iterate. The passes stop when, over every
// constraint with a free particle,
//   max |C(x̃) − (1 − β) C(x₀)| / (|J̃| r) ≤ constraintTolerance   and
//   max |W R₁| ≤ constraintTolerance · max(|v̄| + h|W|(|f| + Σ_c|K_dc||Δx_dc|) + |W Ḡᵀν̄|)
// over the free DOFs; Σ_c|K_dc||Δx_dc| (a spring's k times its length) is the
// size of the force terms that cancel in f near equilibrium, which sets the
// round-off floor of R₁ (without it a stiff cloth hanging still could not get
// below ~1e-9 and ran every pass),
// or after constraintPasses solves (the step is then committed as it stands
// and lastConstraintResidual() says how far it got). A constraint whose
// particles are all pinned (or whose J vanishes) is left out: its impulse is 0,
// it does not count in the stopping test, and it moves nothing — even when it
// cannot be satisfied (a rod between two pins at the wrong length).
// Without constraints there is one pass: Baraff & Witkin's linearly implicit
// step, exact backward Euler for linear forces.
//
// Which Jacobians and which solver:
// - K and D come from Force::addDefiniteJacobians: symmetric negative
//   semi-definite, so A + G is symmetric positive definite on the free degrees
//   of freedom and the matrix above is symmetric quasi-definite for ε > 0:
//   every symmetric permutation has an LDLᵀ factorisation without pivoting
//   (Vanderbei 1995). ε also keeps redundant constraints solvable. The matrix
//   uses J̃ in both off-diagonal blocks (R₁'s exact derivative has Ḡᵀ): the
//   passes then converge to the step above with the ν error contracting by
//   about (h|u|/2r)² per pass, u a rod's relative velocity.
// - Pinned particles (inverse mass 0) are filtered: their rows and columns of A
//   are the identity with a zero right-hand side, so δv = 0 there.
// - The sparsity pattern is analysed once and reused while the forces,
//   constraints and pins keep the same structure.
// - Without constraints, Jacobi-preconditioned conjugate gradient on A alone,
//   warm-started from the last Δv, is the default: measured on 8-way cloth
//   (tests/bench/bench_solvers.cpp) it needs ~5 iterations on ordinary cloth
//   and beats the direct solve (O(n^1.5) fill) by 4-10×; on stiff cloth
//   (k_s h²/m ≫ 1) it needs a few hundred and the two are about even.

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

  // --- constraint rows: C(x₀); C̃, J̃ at x̃; J at x_m; the discrete gradient Ḡ
  linear::ConstraintRows start, iterate, mid;
  std::vector<Eigen::Vector2d> Gbar, probeJ, probeJdot;
  std::vector<char> fixedRow;   // nothing free in the row (all pinned, or J = 0): ν = 0

  // --- residuals of the iterate --------------------------------------------
  Eigen::VectorXd residual;     // (−R₁, −R₂/h): the right-hand side of a pass
  Eigen::VectorXd termScale;    // Σ_c |K_dc| |Δx|: the size of f's cancelling terms
  double constraintResidual = 0.0, momentumResidual = 0.0;
  int passes = 0;

  // --- the linear system: pattern and value slots, LDLᵀ, CG ---------------
  linear::SymmetricPattern pattern;
  std::vector<int> xRow, xCol, vRow, vCol, xSlot, vSlot;
  std::vector<int> diagonalSlot, jSlot, complianceSlot, gSlot;
  std::uint64_t patternStamp = 0;
  bool patternCoupled = false, patternDirect = false, analysed = false;
  linear::Ldlt ldlt;
  linear::CgScratch cg;
  bool usedDirect = true;
  Eigen::VectorXd storedRhs, solution, product, increment, inverseDiagonal, probe;

  // Phases of the step.
  void begin(ParticleSystem& system);
  StepStats lineariseForcesAtStart(ParticleSystem& system, double h);
  void evaluateForces(ParticleSystem& system, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  void lineariseForces(ParticleSystem& system, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  void gatherConstraintRows(ParticleSystem& system, double h);
  void measureResiduals(ParticleSystem& system, double h);
  bool converged() const;
  void assemble(ParticleSystem& system, double h);
  void solvePass(StepStats& stats);
  void commit(ParticleSystem& system, double h) const;

  // Pieces of assemble() and solvePass().
  bool patternMatches(const ParticleSystem& system, bool direct) const;
  void buildPattern(const ParticleSystem& system, bool direct);
  template <class Visit>
  void forEachGeometricStiffnessEntry(const Visit& visit) const;
  void recordSlots(const Eigen::VectorXd& inverseMass);
  bool fillValues(double h, const Eigen::VectorXd& mass, const Eigen::VectorXd& inverseMass);
  void addGeometricStiffness(ParticleSystem& system, double h);
};

ImplicitEulerIntegrator::ImplicitEulerIntegrator() : impl_(std::make_unique<Impl>()) {}
ImplicitEulerIntegrator::~ImplicitEulerIntegrator() = default;
int ImplicitEulerIntegrator::lastPasses() const { return impl_->passes; }
double ImplicitEulerIntegrator::lastConstraintResidual() const { return impl_->constraintResidual; }
double ImplicitEulerIntegrator::lastMomentumResidual() const { return impl_->momentumResidual; }

void ImplicitEulerIntegrator::configure(const IntegratorSettings& settings) {
  settings.validate();
  settings_ = settings.implicitEuler;
}

StepStats ImplicitEulerIntegrator::step(ParticleSystem& system, double h) {
  requireJacobians(system);
  Impl& s = *impl_;
  s.settings = &settings_;
  s.begin(system);
  StepStats stats = s.lineariseForcesAtStart(system, h);
  if (s.coupled) s.gatherConstraintRows(system, h);  // at the first iterate x₀ + h v₀
  s.measureResiduals(system, h);
  for (s.passes = 0;;) {
    s.assemble(system, h);
    s.solvePass(stats);
    ++s.passes;
    // Without constraints one linearly implicit pass is the step (header).
    if (!s.coupled || stats.failure != StepFailure::None) break;
    s.gatherConstraintRows(system, h);
    s.evaluateForces(system, s.xTilde, s.vBar);
    ++stats.forceEvaluations;
    s.measureResiduals(system, h);
    if (s.converged() || s.passes == settings_.constraintPasses) break;
    s.lineariseForces(system, s.xTilde, s.vBar);
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
  x0 = positionsOf(system);
  v0 = velocitiesOf(system);
  vBar = v0;
  // The last step's impulses start the iteration (their tension gives the first
  // pass its geometric stiffness).
  if (nu.size() != m) nu.setZero(m);
  constraintResidual = momentumResidual = 0.0;
  if (coupled) start.gather(system.phase(x0, v0), system.constraints());
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

// At the iterate: C̃ = C(x̃) and J̃ = J(x̃) for the Newton matrix, and the
// discrete gradient Ḡ between x₀ and x̃ (header) along which the impulses act.
void ImplicitEulerIntegrator::Impl::gatherConstraintRows(ParticleSystem& system, double h) {
  const Eigen::VectorXd& w = system.inverseMasses();
  const ConstraintList& constraints = system.constraints();
  xTilde = x0 + h * vBar;
  xMid = x0 + (0.5 * h) * vBar;
  iterate.gather(system.phase(xTilde, vBar), constraints);
  mid.gather(system.phase(xMid, vBar), constraints);
  Gbar = mid.J;  // J(x_m), corrected below
  fixedRow.assign(m, 0);
  for (int k = 0; k < m; ++k) {
    double jjFree = 0.0, dxSquared = 0.0, predicted = 0.0;
    for (int e = iterate.rowStart[k]; e < iterate.rowStart[k + 1]; ++e) {
      const int p = iterate.entryParticle[e];
      const Eigen::Vector2d dx = xTilde.segment<2>(2 * p) - x0.segment<2>(2 * p);
      dxSquared += dx.squaredNorm();
      predicted += Gbar[e].dot(dx);
      if (w[p] != 0.0) jjFree += iterate.J[e].squaredNorm();
    }
    fixedRow[k] = jjFree == 0.0;
    if (fixedRow[k]) nu[k] = 0.0;
    // Gonzalez's correction makes Ḡ Δx = C(x̃) − C(x₀) exactly. It is O(|Δx|²)
    // and zero for quadratic C; below a relative step of 1e-6 it would be
    // rounding divided by |Δx|² and is left out (its effect is then O(|Δx|³)).
    const double scale = constraints[k]->lengthScale() > 0.0 ? constraints[k]->lengthScale() : 1.0;
    if (dxSquared <= 1e-12 * scale * scale) continue;
    const double correction = (iterate.C[k] - start.C[k] - predicted) / dxSquared;
    for (int e = iterate.rowStart[k]; e < iterate.rowStart[k + 1]; ++e) {
      const int p = iterate.entryParticle[e];
      Gbar[e] += correction * (xTilde.segment<2>(2 * p) - x0.segment<2>(2 * p));
    }
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
  constraintResidual = momentumResidual = 0.0;
  if (!coupled) return;
  for (int k = 0; k < m; ++k) {
    if (fixedRow[k]) continue;
    double jj = 0.0;
    for (int e = iterate.rowStart[k]; e < iterate.rowStart[k + 1]; ++e) {
      const int p = iterate.entryParticle[e];
      if (w[p] == 0.0) continue;
      r1.segment<2>(2 * p) -= nu[k] * Gbar[e];
      jj += iterate.J[e].squaredNorm();
    }
    const double r2 = iterate.C[k] - (1.0 - beta) * start.C[k];
    residual[dofs + k] = -r2 / h;
    const double length = system.constraints()[k]->lengthScale();
    constraintResidual = std::max(constraintResidual, std::abs(r2) / (std::sqrt(jj) * (length > 0.0 ? length : 1.0)));
  }
  // The size of the force terms that cancel in f near equilibrium: Σ_c |K_dc|
  // |x_p(d) − x_p(c)| over entries coupling two particles (a spring's k times
  // its length). f's round-off is about ε times it, so it belongs in the scale.
  termScale.setZero(dofs);
  for (const auto& t : dfdx) {
    const int p = t.row() / 2, q = t.col() / 2;
    if (p != q) termScale[t.row()] += std::abs(t.value()) * (x0.segment<2>(2 * p) - x0.segment<2>(2 * q)).norm();
  }
  // Velocity scale of R₁/m: the sizes of the terms it balances, |v̄|, h|W f|,
  // h|W| Σ|K||Δx|, |W Ḡᵀν̄|.
  double velocityScale = 0.0, worst = 0.0;
  for (int d = 0; d < dofs; ++d) {
    const double wd = w[d / 2];
    if (wd == 0.0) continue;
    const double impulse = mass[d / 2] * (vBar[d] - v0[d]) - h * f[d] + r1[d];  // −(Ḡᵀν̄)_d
    velocityScale = std::max(velocityScale, std::abs(vBar[d]) + h * wd * (std::abs(f[d]) + termScale[d]) +
                                                wd * std::abs(impulse));
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
  usedDirect = coupled || settings->solver == ImplicitLinearSolver::Direct;
  if (!patternMatches(system, usedDirect)) buildPattern(system, usedDirect);
  if (!fillValues(h, system.masses(), system.inverseMasses())) {
    buildPattern(system, usedDirect);
    fillValues(h, system.masses(), system.inverseMasses());
  }
  if (coupled && settings->geometricStiffness) addGeometricStiffness(system, h);
}

// One Newton solve for (δv, δν) in the pattern's stored numbering, then the
// iterate moves: v̄ += δv, ν̄ += δν.
void ImplicitEulerIntegrator::Impl::solvePass(StepStats& stats) {
  pattern.toStored(residual, storedRhs);
  if (usedDirect) {
    ++stats.factorizations;
    // A failed factorisation (only a blown-up, non-finite state gets here:
    // the matrix is quasi-definite) is reported as a failed solve.
    if (!ldlt.factorize(pattern.matrix())) {
      solution.setConstant(storedRhs.size(), NAN);
    } else {
      ldlt.solve(storedRhs, solution);
      const double bNorm = storedRhs.norm();
      pattern.multiplyStored(solution, product);
      stats.maxResidual = std::max(stats.maxResidual, bNorm > 0.0 ? (storedRhs - product).norm() / bNorm : 0.0);
    }
  } else {
    // Jacobi-preconditioned CG on A alone (no constraints, natural order: the
    // stored numbering is the DOF numbering), warm-started from the last
    // step's Δv, which solution still holds. Pinned rows are the identity with
    // a zero right-hand side, so they stay 0.
    if (solution.size() != dofs || !solution.allFinite()) solution.setZero(dofs);
    inverseDiagonal.resize(dofs);
    for (int d = 0; d < dofs; ++d) {
      const double a = pattern.values()[diagonalSlot[d]];
      inverseDiagonal[d] = a > 0.0 ? 1.0 / a : 1.0;
    }
    linear::CgSettings cgSettings;
    cgSettings.tolerance = settings->cgTolerance;
    cgSettings.maxIterations = settings->cgMaxIterations;
    const linear::CgResult result = linear::conjugateGradient(
        [&](const Eigen::VectorXd& y, Eigen::VectorXd& out) { pattern.multiplyStored(y, out); },
        [&](const Eigen::VectorXd& r, Eigen::VectorXd& z) { z = inverseDiagonal.cwiseProduct(r); }, storedRhs,
        solution, cgSettings, cg);
    stats.cgIterations += result.iterations;
    stats.maxResidual = std::max(stats.maxResidual, result.relativeResidual);
  }
  ++stats.solves;
  if (!solution.allFinite()) {
    stats.failure = StepFailure::SolveFailed;
    return;
  }
  pattern.fromStored(solution, increment);
  vBar += increment.head(dofs);
  for (int k = 0; k < m; ++k)
    if (!fixedRow[k]) nu[k] += increment[dofs + k];
}

void ImplicitEulerIntegrator::Impl::commit(ParticleSystem& system, double h) const {
  velocitiesOf(system) = vBar;  // a failed solve leaves the last finite iterate
  positionsOf(system) = x0 + h * vBar;
}

// --- the linear system -------------------------------------------------------

bool ImplicitEulerIntegrator::Impl::patternMatches(const ParticleSystem& system, bool direct) const {
  // Each triplet's position is checked while fillValues() scatters it.
  return analysed && system.structureStamp() == patternStamp && coupled == patternCoupled &&
         direct == patternDirect && dfdx.size() == xRow.size() && dfdv.size() == vRow.size();
}

// Calls visit(row, col) for every DOF pair of G, in the loop order of
// addGeometricStiffness: constraint k, then column (particle b, axis c), then row (a, r).
template <class Visit>
void ImplicitEulerIntegrator::Impl::forEachGeometricStiffnessEntry(const Visit& visit) const {
  for (int k = 0; k < m; ++k)
    for (int eb = iterate.rowStart[k]; eb < iterate.rowStart[k + 1]; ++eb)
      for (int c = 0; c < 2; ++c)
        for (int ea = iterate.rowStart[k]; ea < iterate.rowStart[k + 1]; ++ea)
          for (int r = 0; r < 2; ++r) visit(2 * iterate.entryParticle[ea] + r, 2 * iterate.entryParticle[eb] + c);
}

// The KKT matrix: A on the 2n velocity unknowns, then one row per constraint,
// in a SymmetricPattern: AMD-ordered for the direct solve, natural for CG,
// whose products are faster in the mesh's own order. Every value's slot is
// recorded so that fillValues() is a scatter, with no search and no allocation.
void ImplicitEulerIntegrator::Impl::buildPattern(const ParticleSystem& system, bool direct) {
  const Eigen::VectorXd& inverseMass = system.inverseMasses();
  auto free = [&](int dof) { return inverseMass[dof / 2] != 0.0; };
  pattern.reset(dofs + m);
  for (const Triplets* list : {&dfdx, &dfdv})
    for (const auto& t : *list)
      if (free(t.row()) && free(t.col())) pattern.add(t.row(), t.col());
  for (int k = 0; k < m; ++k) {
    for (int e = iterate.rowStart[k]; e < iterate.rowStart[k + 1]; ++e)
      if (inverseMass[iterate.entryParticle[e]] != 0.0)
        for (int r = 0; r < 2; ++r) pattern.add(dofs + k, 2 * iterate.entryParticle[e] + r);
  }
  // Geometric stiffness couples every pair of free particles of a constraint.
  forEachGeometricStiffnessEntry([&](int row, int col) {
    if (free(row) && free(col)) pattern.add(row, col);
  });
  pattern.finish(direct ? linear::SymmetricPattern::Ordering::Amd : linear::SymmetricPattern::Ordering::Natural);
  recordSlots(inverseMass);
  patternStamp = system.structureStamp();
  patternCoupled = coupled;
  patternDirect = direct;
  ldlt.forgetAnalysis();  // analysed on the first factorisation
  analysed = true;
}

// Where each value of the matrix goes: the diagonal of A, every force
// triplet, every free block of J̃, each row's compliance, every entry of G
// (−1: a pinned DOF, dropped).
void ImplicitEulerIntegrator::Impl::recordSlots(const Eigen::VectorXd& inverseMass) {
  auto free = [&](int dof) { return inverseMass[dof / 2] != 0.0; };
  diagonalSlot.resize(dofs);
  for (int d = 0; d < dofs; ++d) diagonalSlot[d] = pattern.slot(d, d);
  auto record = [&](const Triplets& list, std::vector<int>& rows, std::vector<int>& cols, std::vector<int>& slots) {
    rows.resize(list.size());
    cols.resize(list.size());
    slots.resize(list.size());
    for (std::size_t k = 0; k < list.size(); ++k) {
      rows[k] = list[k].row();
      cols[k] = list[k].col();
      slots[k] = free(rows[k]) && free(cols[k]) ? pattern.slot(rows[k], cols[k]) : -1;
    }
  };
  record(dfdx, xRow, xCol, xSlot);
  record(dfdv, vRow, vCol, vSlot);
  jSlot.assign(2 * (coupled ? iterate.entries() : 0), -1);
  complianceSlot.resize(m);
  for (int k = 0; k < m; ++k) {
    for (int e = iterate.rowStart[k]; e < iterate.rowStart[k + 1]; ++e)
      if (inverseMass[iterate.entryParticle[e]] != 0.0)
        for (int r = 0; r < 2; ++r) jSlot[2 * e + r] = pattern.slot(dofs + k, 2 * iterate.entryParticle[e] + r);
    complianceSlot[k] = pattern.slot(dofs + k, dofs + k);
  }
  gSlot.clear();
  forEachGeometricStiffnessEntry([&](int row, int col) {
    gSlot.push_back(free(row) && free(col) ? pattern.slot(row, col) : -1);
  });
}

// Values of the stored KKT triangle: A = M − h D − h² K, J̃ and −E. A triplet
// (r, c, a) of K or D lands in the slot of (r, c) — shared with (c, r) — with
// weight ½ off the diagonal, so the matrix is the symmetric part of what the
// forces report (the definite Jacobians already are). Returns false, having
// written only part of the values, when a triplet is not where the pattern has it.
bool ImplicitEulerIntegrator::Impl::fillValues(double h, const Eigen::VectorXd& mass,
                                               const Eigen::VectorXd& inverseMass) {
  double* value = pattern.values();
  std::fill(value, value + pattern.nonZeros(), 0.0);
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
    for (int e = iterate.rowStart[k]; e < iterate.rowStart[k + 1]; ++e) {
      const double w = inverseMass[iterate.entryParticle[e]];
      if (w == 0.0) continue;
      diagonal += w * iterate.J[e].squaredNorm();
      for (int r = 0; r < 2; ++r) value[jSlot[2 * e + r]] = fixedRow[k] ? 0.0 : iterate.J[e][r];
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
  double* value = pattern.values();
  const double weight = 0.5 * h;
  probe.setZero(dofs);
  std::size_t g = 0;
  for (int k = 0; k < m; ++k) {
    const std::vector<int>& ps = constraints[k]->particles();
    const std::size_t count = ps.size();
    const double tension = fixedRow[k] ? 0.0 : std::max(nu[k], 0.0);
    if (probeJ.size() < count) probeJ.resize(count), probeJdot.resize(count);
    ConstraintRow row;
    row.J = probeJ.data();
    row.Jdot = probeJdot.data();
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
            value[gSlot[g]] += (diagonal ? weight : 0.5 * weight) * tension * probeJdot[a][r];
          }
      }
  }
}

}  // namespace particles

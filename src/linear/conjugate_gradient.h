#pragma once
// Preconditioned conjugate gradient (Hestenes–Stiefel; Saad, "Iterative
// Methods for Sparse Linear Systems", Alg. 9.1) on A x = b, A symmetric
// positive (semi-)definite, given as a matrix-free operator:
//   r₀ = b − A x₀,  z₀ = M⁻¹ r₀,  p₀ = z₀;  each iteration
//   α = rᵀz / pᵀAp,  x += α p,  r −= α A p,  z = M⁻¹ r,  p = z + (r⁺ᵀz⁺ / rᵀz) p,
// until |r| ≤ tolerance·|b| or maxIterations, or until the program's cancel
// flag goes up (particles/cancel.h: a signal during a long solve). When A is only semi-definite
// and b has a part outside its range (a constraint set that lost rank) CG
// meets a direction with pᵀAp ≈ 0; it stops there with the finite x it has
// (curvature floor below). The operator and preconditioner are callables
//   apply(const VectorXd& y, VectorXd& out)          out = A y
//   precondition(const VectorXd& r, VectorXd& z)     z = M⁻¹ r
// and the scratch vectors are the caller's, so a step loop allocates nothing.
#include <Eigen/Core>

#include "particles/cancel.h"

namespace particles::linear {

struct CgSettings {
  double tolerance = 1e-8;     // stop when |r| ≤ tolerance·|b| (relative residual)
  int maxIterations = 100;     // iteration cap (≥ 0)
  // Stop when pᵀAp ≤ curvatureFloor·|p|² (no curvature left; 0: only a
  // non-positive or non-finite pᵀAp stops). A scale of A's diagonal times a
  // small factor suits a semi-definite A.
  double curvatureFloor = 0.0;
};

struct CgResult {
  int iterations = 0;
  double relativeResidual = 0.0;  // |r|/|b| at exit (0 when b = 0)
};

struct CgScratch {
  Eigen::VectorXd r, z, p, Ap;
};

// Solves A x = b from the guess in x (sized like b by the caller; b = 0 gives x = 0).
template <class Apply, class Precondition>
CgResult conjugateGradient(const Apply& apply, const Precondition& precondition, const Eigen::VectorXd& b,
                           Eigen::VectorXd& x, const CgSettings& settings, CgScratch& scratch) {
  CgResult result;
  const double bNorm = b.norm();
  if (bNorm == 0.0) {
    x.setZero(b.size());
    return result;
  }
  Eigen::VectorXd &r = scratch.r, &z = scratch.z, &p = scratch.p, &Ap = scratch.Ap;
  apply(x, Ap);
  r = b - Ap;
  precondition(r, z);
  p = z;
  double rz = r.dot(z);
  const double target = settings.tolerance * bNorm;
  double rNorm = r.norm();
  while (result.iterations < settings.maxIterations && rNorm > target && !cancelRequested()) {
    apply(p, Ap);
    const double pAp = p.dot(Ap);
    // |p|² is needed only against a positive floor (0·|p|² = 0 otherwise).
    const double floor = settings.curvatureFloor > 0.0 ? settings.curvatureFloor * p.squaredNorm() : 0.0;
    if (!(pAp > floor)) break;
    const double alpha = rz / pAp;
    x += alpha * p;
    r -= alpha * Ap;
    rNorm = r.norm();
    precondition(r, z);
    const double rzNext = r.dot(z);
    p = z + (rzNext / rz) * p;
    rz = rzNext;
    ++result.iterations;
  }
  result.relativeResidual = rNorm / bNorm;
  return result;
}

}  // namespace particles::linear

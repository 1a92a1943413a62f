#pragma once
// Straight lines of compliant distance constraints hanging from a held
// particle, each solved directly: a block Gauss–Seidel step whose block is a
// whole line (XpbdSettings::lines).
//
// A line is constraints c_t between particles p_t and p_{t+1}, t < m, with a
// constant index step p_{t+1} − p_t (a column, row or diagonal of a grid, a
// strand of hair), starting at a held particle p_0: one pinned (w = 0) or on
// a one-particle hard constraint h (a line, a wire) with gradient g at p_0.
// With d_t = x_{p_t} − x_{p_{t+1}}, u_t = d_t/|d_t| the system of XPBD's
// damped update (xpbd/multiplier.h) for every row of the line at once,
//   (1 + γ_t) ∇C_t W Σ_s ∇C_sᵀ Δλ_s + α̃_t Δλ_t = −C_t − α̃_t λ_t − γ_t ∇C_t·(x − xⁿ),
// with the hold's hard row g·W(g Δλ_h + u_0 Δλ_0) = −C_h first, is
// tridiagonal:
//   diagonal      (1 + γ_t)(w_{p_t} + w_{p_{t+1}}) + α̃_t,   w_{p_0} |g|² for h,
//   c_t, c_{t+1}  −(1 + γ) w_{p_{t+1}} u_t·u_{t+1} (γ of the row),
//   h, c_0        w_{p_0} g·u_0 (times 1 + γ_0 in c_0's row),
// solved by elimination along the line (Thomas), then
//   x_{p_t} += w_{p_t} (u_t Δλ_t − u_{t−1} Δλ_{t−1})   (+ g Δλ_h at p_0).
// Gauss–Seidel carries a hanging line's load one constraint per pass; the
// solve carries it the whole length into the hold.
//
// Which lines: at each held particle, of the straight lines starting there
// (two or more constraints), the one with the largest (particles on it not
// held themselves) × |ĝ·u_0| (1 for a pin), ties to the shorter rest length,
// then the smaller step; none when that is 0 (a line along a rail); lines taken in the order of the
// held particles, one that would share a particle with a line already taken
// left out. Lines share no particle, so they are solved on any thread with
// the same bits. The constraints on no line are left to DistanceBatch.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "particles/constraint.h"
#include "particles/phase.h"
#include "xpbd/distance.h"

namespace particles {

class HangingLines {
 public:
  // Finds the lines among `distances` (held particles: pins and the
  // one-particle constraints of `holds`, their gradients taken at s) and
  // returns the constraints on none, in their order.
  std::vector<CompliantDistance> build(const std::vector<CompliantDistance>& distances, const ConstraintList& holds,
                                       const Phase& s);
  void clear() { *this = HangingLines(); }
  std::size_t lines() const { return holds_.size(); }
  std::size_t constraints() const { return rest_.size(); }

  // Solves every line at positions x (flat, 2n) with xⁿ = xn, v and masses
  // for the holds' kernels; the multipliers start at 0 on pass 0 and are
  // kept between passes.
  void project(const Eigen::VectorXd& xn, Eigen::VectorXd& x, const Eigen::VectorXd& v, const Eigen::VectorXd& mass,
               const Eigen::VectorXd& inverseMass, int pass);

 private:
  // Up to kLanes lines of one step and length whose first particles are
  // first + laneStride·q, solved side by side (lane q), so that the
  // eliminations' divisions overlap. Its constraints are [begin, begin +
  // lanes·length) of the arrays below, row t of lane q at begin + t·lanes + q;
  // its lines' holds are holds_[line, line + lanes).
  struct Bundle {
    std::size_t begin, line;
    int first, laneStride, step, length, lanes;
  };
  void solve(std::size_t bundle, const Phase& s, const double* xn, double* x, bool start);

  std::vector<Bundle> bundles_;
  std::vector<const Constraint*> holds_;  // each line's one-particle constraint at p_0, or null (a pin)
  std::vector<double> rest_, alphaTilde_, gamma_, lambda_;
  // Scratch per row, the holds' (row 0 of each bundle) and the constraints'
  // (rows 1…length), lane by lane: directions, the eliminated diagonal, the
  // upper band and the right side (Δλ once solved).
  std::vector<double> ux_, uy_, diagonal_, upper_, rhs_;
};

}  // namespace particles

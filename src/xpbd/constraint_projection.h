#pragma once
// Hard constraints (rods, wires, lines) in position form, through their own C
// and J kernels.
#include <vector>

#include <Eigen/Core>

#include "particles/constraint.h"
#include "xpbd/multiplier.h"

namespace particles {

// One zero-compliance projection of a constraint at positions x (α = 0 in
// xpbd/multiplier.h): with C and the blocks J_k of ∂C/∂x from
// Constraint::evaluate,
//   Δλ = −C / Σ_k w_k |J_k|²,   x_k += w_k J_k Δλ,
// a Newton step on C along W Jᵀ. The squared rod (C = |d|² − r², J = 2d) and
// the root rod (C = |d| − r, J = u) reach the same |d| = r. blocks is scratch
// of at least particles().size() entries.
void projectConstraint(const Constraint& constraint, const Eigen::VectorXd& v,
                         const Eigen::VectorXd& mass, const Eigen::VectorXd& inverseMass,
                         Eigen::VectorXd& x, std::vector<Eigen::Vector2d>& blocks);

}  // namespace particles

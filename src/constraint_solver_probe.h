#pragma once
// The gathered rows of a ConstraintSolver's last solve as dense matrices, for
// the tests that check them against finite differences and a dense solve, and
// which pass formed them.
#include <Eigen/Core>

#include "particles/constraint_solver.h"

namespace particles {

struct ConstraintSolverProbe {
  static Eigen::MatrixXd denseJ(const ConstraintSolver& solver, int particleCount);     // m × 2n
  static Eigen::MatrixXd denseJdot(const ConstraintSolver& solver, int particleCount);  // m × 2n
  // The last solve's rows came from a chain of rods' own pass (constraints/rod_chain.h).
  static bool rodChainPass(const ConstraintSolver& solver);
};

}  // namespace particles

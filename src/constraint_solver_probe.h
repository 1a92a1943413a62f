#pragma once
// The gathered rows of a ConstraintSolver's last solve as dense matrices, for
// the tests that check them against finite differences and a dense solve.
#include <Eigen/Core>

#include "particles/constraint_solver.h"

namespace particles {

struct ConstraintSolverProbe {
  static Eigen::MatrixXd denseJ(const ConstraintSolver& solver, int particleCount);     // m × 2n
  static Eigen::MatrixXd denseJdot(const ConstraintSolver& solver, int particleCount);  // m × 2n
};

}  // namespace particles

#pragma once
// A chain of rods as the constraint solve meets it: every constraint a rod
// (particles/constraints/rod.h), each sharing particles only with the rods
// before and after it in the list, so that J W Jᵀ is tridiagonal (the
// solver's chain, solved by linear/tridiagonal.h). One pass over the rods
// evaluates each rod's kernel (rodKernel, the one definition of its C, Ċ, J,
// J̇) and forms from it, with no generic gather of rows,
//   b_k = −J̇_k q̇ − J_k W Q − k_s C_k − k_d Ċ_k          (linear::constraintRhs),
//   (J W Jᵀ)_kk = w_i |J_k,i|² + w_j |J_k,j|²,
//   (J W Jᵀ)_k,k+1 = Σ_p w_p J_k,p · J_k+1,p   over the particles p rods k and k + 1 share,
// writing the rows (C, Ċ, J, J̇) where ConstraintRows::gather would, so that
// what reads the rows afterwards (the probe of the tests) sees the same.
#include <vector>

#include <Eigen/Core>

#include "linear/constraint_rows.h"
#include "linear/tridiagonal.h"
#include "particles/constraint.h"
#include "particles/constraints/rod.h"

namespace particles {

class RodChain {
 public:
  // Takes the rods of `constraints`, already found to be a chain (their rows
  // gathered, two entries a rod). False (and nothing kept) when one is not a rod.
  bool build(const ConstraintList& constraints);

  struct Output {
    linear::ConstraintRows& rows;  // C, Ċ, J, J̇ (rows built by gather, two entries a rod)
    Eigen::VectorXd& b;
    Eigen::VectorXd& diagonal;           // (J W Jᵀ)_kk
    std::vector<double>& bandDiagonal;   // the same, as the tridiagonal solve reads it
    std::vector<double>& upper;          // (J W Jᵀ)_k,k+1
    linear::Tridiagonal& tridiagonal;    // factorised row by row as the pass goes (no shift), b forward-substituted
  };
  struct Formed {
    bool valid = false;  // false: `constraints` are no longer the rods built from; read nothing
    double largest = 0.0, smallest = 0.0;  // max_k and min_k of (J W Jᵀ)_kk
  };
  // The pass above at s with forces Q = f, which also factorises J W Jᵀ
  // (Tridiagonal::row) while the pass's own work hides the recursion's latency.
  Formed form(const Phase& s, const ConstraintList& constraints, const Eigen::VectorXd& f, double stiffness,
              double damping, const Output& out) const;
  // f += Jᵀ λ.
  void addJtTimes(const linear::ConstraintRows& rows, const Eigen::VectorXd& lambda, Eigen::VectorXd& f) const;

 private:
  struct Link {
    const RodConstraint* rod;
    int i, j;            // its particles
    int shared;          // how many of them rod k + 1 names too (0, 1 or 2)
    int mine[2], next[2];  // for each: its entry (0 or 1) in this rod and in rod k + 1
  };
  std::vector<Link> links_;
};

}  // namespace particles

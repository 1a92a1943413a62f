#pragma once
// The constraint rows of one phase: for constraint k, C_k, Ċ_k and its blocks
// of J = ∂C/∂q and J̇, one 2-vector per particle the constraint names, in
// compressed form: entries rowStart[k] .. rowStart[k+1]−1 belong to row k,
// entry e is particle entryParticle[e] with blocks J[e], Jdot[e].
#include <vector>

#include <Eigen/Core>

#include "particles/constraint.h"

namespace particles::linear {

struct ConstraintRows {
  std::vector<int> rowStart{0};
  std::vector<int> entryParticle;
  std::vector<Eigen::Vector2d> J, Jdot;
  Eigen::VectorXd C, Cdot;

  int size() const { return static_cast<int>(rowStart.size()) - 1; }  // m
  int entries() const { return rowStart.back(); }

  // Evaluates every constraint at s into the arrays, reusing their storage.
  // Returns true when the rows name other particles than at the last gather
  // (the structure changed: patterns built from the rows are stale).
  bool gather(const Phase& s, const ConstraintList& constraints);

  // diag(J W Jᵀ)_k = Σ_e w_p |J_e|², W = diag(inverse masses w) per particle.
  void diagonalOfJWJt(const Eigen::VectorXd& w, Eigen::VectorXd& out) const;
  // out = J W Jᵀ y, never formed: scatter = W Jᵀ y (2n), then out = J scatter.
  void applyJWJt(const Eigen::VectorXd& w, const Eigen::VectorXd& y, Eigen::VectorXd& out,
                 Eigen::VectorXd& scatter) const;
  // f += Jᵀ λ.
  void addJtTimes(const Eigen::VectorXd& lambda, Eigen::VectorXd& f) const;
  // J_k · v and J̇_k · v for a 2n vector v.
  double rowTimes(int k, const Eigen::VectorXd& v) const;
  double rowDotTimes(int k, const Eigen::VectorXd& v) const;
  // J and J̇ as dense m × 2n matrices (tests compare against a dense solve).
  Eigen::MatrixXd denseJ(int particleCount) const;
  Eigen::MatrixXd denseJdot(int particleCount) const;
};

}  // namespace particles::linear

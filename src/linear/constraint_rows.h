#pragma once
// The constraint rows of one phase: for constraint k, C_k, Ċ_k and its blocks
// of J = ∂C/∂q and J̇, one 2-vector per particle the constraint names, in
// compressed form: entries rowStart[k] .. rowStart[k+1]−1 belong to row k,
// entry e is particle entryParticle[e] with blocks J[e], Jdot[e].
#include <vector>

#include <Eigen/Core>

#include "particles/constraint.h"

namespace particles::linear {

// Row k of the constraint solve's right-hand side from its products J̇_k q̇
// and J_k W Q: b_k = −J̇_k q̇ − J_k W Q − k_s C_k − k_d Ċ_k.
inline double constraintRhs(double jdotQdot, double jwq, double C, double Cdot, double stiffness, double damping) {
  return -jdotQdot - jwq - stiffness * C - damping * Cdot;
}

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

  // (J W Jᵀ)_kk = Σ_e w_p |J_e|² over row k's entries e (particle p), W the
  // inverse masses per particle.
  double diagonalOfJWJt(int k, const Eigen::VectorXd& w) const {
    double sum = 0.0;
    for (int e = rowStart[k]; e < rowStart[k + 1]; ++e) sum += w[entryParticle[e]] * J[e].squaredNorm();
    return sum;
  }
  // For every row k, the right-hand side of the constraint solve and the
  // diagonal of J W Jᵀ, in one pass over the entries:
  //   b_k = −J̇_k q̇ − J_k W Q − k_s C_k − k_d Ċ_k,   (J W Jᵀ)_kk = Σ_e w_p |J_e|²,
  // with Q the accumulated forces f. Returns max_k (J W Jᵀ)_kk (0 for m = 0).
  double rhsAndDiagonal(const Eigen::VectorXd& w, const Eigen::VectorXd& v, const Eigen::VectorXd& f,
                        double stiffness, double damping, Eigen::VectorXd& b, Eigen::VectorXd& diagonal) const;
  // out = J W Jᵀ y, never formed: scatter = W Jᵀ y (2n), then out = J scatter.
  void applyJWJt(const Eigen::VectorXd& w, const Eigen::VectorXd& y, Eigen::VectorXd& out,
                 Eigen::VectorXd& scatter) const;
  // f += Jᵀ λ.
  void addJtTimes(const Eigen::VectorXd& lambda, Eigen::VectorXd& f) const;
  // J_k · u and J̇_k · u for a 2n vector u.
  double rowTimes(int k, const Eigen::VectorXd& u) const { return rowTimes(J, k, u); }
  double rowDotTimes(int k, const Eigen::VectorXd& u) const { return rowTimes(Jdot, k, u); }
  // J and J̇ as dense m × 2n matrices (tests compare against a dense solve).
  Eigen::MatrixXd denseJ(int particleCount) const;
  Eigen::MatrixXd denseJdot(int particleCount) const;

 private:
  double rowTimes(const std::vector<Eigen::Vector2d>& blocks, int k, const Eigen::VectorXd& u) const {
    double sum = 0.0;
    for (int e = rowStart[k]; e < rowStart[k + 1]; ++e) sum += blocks[e].dot(u.segment<2>(2 * entryParticle[e]));
    return sum;
  }
};

}  // namespace particles::linear

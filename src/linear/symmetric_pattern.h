#pragma once
// The sparsity pattern of a symmetric size × size matrix S, stored the way a
// sparse LDLᵀ wants it: the upper triangle of P S Pᵀ in compressed columns,
// P a fill-reducing (AMD) ordering or the identity, so that the factorisation
// reads the stored matrix as it is, with no per-solve permuted copy. Unknown i
// of S is row order()[i] of the stored matrix. The pattern is built once per
// structure; slot(r, c) then says where S_rc (= S_cr) sits in values(), so
// each step only writes values.
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace particles::linear {

using SparseMatrix = Eigen::SparseMatrix<double>;  // column-major, int indices

class SymmetricPattern {
 public:
  enum class Ordering {
    Natural,  // P = I: a mesh's own numbering, best for CG's products
    Amd,      // approximate minimum degree: least fill in the LDLᵀ factor
  };

  // Starts a pattern of size × size; the diagonal is always part of it.
  void reset(int size);
  // Entry (r, c) and its mirror (c, r); duplicates are merged.
  void add(int r, int c);
  // Orders the unknowns and stores the upper triangle, values zero.
  void finish(Ordering ordering);

  int size() const { return static_cast<int>(order_.size()); }
  // Index of S_rc (r, c in the original numbering) in values().
  int slot(int r, int c) const;
  const Eigen::VectorXi& order() const { return order_; }
  SparseMatrix& matrix() { return matrix_; }
  const SparseMatrix& matrix() const { return matrix_; }
  double* values() { return matrix_.valuePtr(); }
  int nonZeros() const { return static_cast<int>(matrix_.nonZeros()); }

  // Between the original and the stored numbering: stored[order[i]] = original[i].
  void toStored(const Eigen::VectorXd& original, Eigen::VectorXd& stored) const;
  void fromStored(const Eigen::VectorXd& stored, Eigen::VectorXd& original) const;
  // y = (P S Pᵀ) x, both in the stored numbering.
  void multiplyStored(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
    y.noalias() = matrix_.selfadjointView<Eigen::Upper>() * x;
  }

 private:
  int pending_ = 0;  // size given to reset()
  std::vector<std::pair<int, int>> entries_;
  SparseMatrix matrix_;
  Eigen::VectorXi order_;
};

}  // namespace particles::linear

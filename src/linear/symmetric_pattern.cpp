#include "linear/symmetric_pattern.h"

#include <algorithm>

#include <Eigen/OrderingMethods>

namespace particles::linear {

void SymmetricPattern::reset(int size) {
  pending_ = size;
  entries_.clear();
  for (int i = 0; i < size; ++i) entries_.emplace_back(i, i);
}

void SymmetricPattern::add(int r, int c) { entries_.emplace_back(r, c); }

void SymmetricPattern::finish(Ordering ordering) {
  const int size = pending_;
  order_.resize(size);
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(2 * entries_.size());
  if (ordering == Ordering::Amd) {
    for (const auto& [r, c] : entries_) {
      triplets.emplace_back(r, c, 1.0);
      triplets.emplace_back(c, r, 1.0);
    }
    SparseMatrix symmetric(size, size);
    symmetric.setFromTriplets(triplets.begin(), triplets.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int>()(symmetric, inverse);
    // AMD gives the inverse permutation: unknown inverse[i] goes to row i.
    for (int i = 0; i < size; ++i) order_[inverse.indices()[i]] = i;
  } else {
    for (int i = 0; i < size; ++i) order_[i] = i;
  }
  triplets.clear();
  for (const auto& [r, c] : entries_) {
    const int a = order_[r], b = order_[c];
    triplets.emplace_back(std::min(a, b), std::max(a, b), 0.0);
  }
  matrix_.resize(size, size);
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();
  entries_.clear();
  entries_.shrink_to_fit();
}

int SymmetricPattern::slot(int r, int c) const {
  const int a = order_[r], b = order_[c];
  const int row = std::min(a, b), column = std::max(a, b);
  const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[column];
  const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[column + 1];
  return static_cast<int>(std::lower_bound(begin, end, row) - matrix_.innerIndexPtr());
}

void SymmetricPattern::toStored(const Eigen::VectorXd& original, Eigen::VectorXd& stored) const {
  const int size = this->size();
  stored.resize(size);
  for (int i = 0; i < size; ++i) stored[order_[i]] = original[i];
}

void SymmetricPattern::fromStored(const Eigen::VectorXd& stored, Eigen::VectorXd& original) const {
  const int size = this->size();
  original.resize(size);
  for (int i = 0; i < size; ++i) original[i] = stored[order_[i]];
}

}  // namespace particles::linear

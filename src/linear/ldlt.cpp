#include "linear/ldlt.h"

namespace particles::linear {

Ldlt::Ldlt() : solver_(std::make_unique<Solver>()) {}
Ldlt::~Ldlt() = default;
Ldlt::Ldlt(Ldlt&&) noexcept = default;
Ldlt& Ldlt::operator=(Ldlt&&) noexcept = default;

void Ldlt::analyze(const SparseMatrix& upper) {
  solver_->analyzePattern(upper);
  analysed_ = true;
}

bool Ldlt::factorize(const SparseMatrix& upper, double shift) {
  if (!analysed_) analyze(upper);
  solver_->setShift(shift);
  solver_->factorize(upper);
  return solver_->info() == Eigen::Success;
}

double Ldlt::smallestPivot() const { return solver_->diagonal().minCoeff(); }

void Ldlt::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const { x = solver_->solve(b); }

}  // namespace particles::linear

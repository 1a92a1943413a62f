#include "linear/constraint_rows.h"

namespace particles::linear {

bool ConstraintRows::gather(const Phase& s, const ConstraintList& constraints) {
  const int m = static_cast<int>(constraints.size());
  // Any change in which particles the rows name is noticed here, while the
  // rows are written anyway.
  bool changed = static_cast<int>(rowStart.size()) != m + 1;
  rowStart.resize(m + 1);
  rowStart[0] = 0;
  for (int k = 0; k < m; ++k) {
    const int next = rowStart[k] + static_cast<int>(constraints[k]->particles().size());
    changed |= rowStart[k + 1] != next;
    rowStart[k + 1] = next;
  }
  const int count = rowStart[m];
  changed |= static_cast<int>(entryParticle.size()) != count;
  entryParticle.resize(count);
  J.resize(count);
  Jdot.resize(count);
  C.resize(m);
  Cdot.resize(m);
  for (int k = 0; k < m; ++k) {
    const Constraint& c = *constraints[k];
    ConstraintRow row;
    row.J = &J[rowStart[k]];
    row.Jdot = &Jdot[rowStart[k]];
    c.evaluate(s, row);
    C[k] = row.C;
    Cdot[k] = row.Cdot;
    for (int e = rowStart[k], n = 0; e < rowStart[k + 1]; ++e, ++n) {
      changed |= entryParticle[e] != c.particles()[n];
      entryParticle[e] = c.particles()[n];
    }
  }
  return changed;
}

void ConstraintRows::applyJWJt(const Eigen::VectorXd& w, const Eigen::VectorXd& y, Eigen::VectorXd& out,
                               Eigen::VectorXd& scatter) const {
  const int m = size();
  scatter.setZero(2 * w.size());
  for (int k = 0; k < m; ++k)
    for (int e = rowStart[k]; e < rowStart[k + 1]; ++e) scatter.segment<2>(2 * entryParticle[e]) += J[e] * y[k];
  out.resize(m);
  for (int k = 0; k < m; ++k) {
    double sum = 0.0;
    for (int e = rowStart[k]; e < rowStart[k + 1]; ++e) {
      const int p = entryParticle[e];
      sum += w[p] * J[e].dot(scatter.segment<2>(2 * p));
    }
    out[k] = sum;
  }
}

namespace {
Eigen::MatrixXd dense(const ConstraintRows& rows, const std::vector<Eigen::Vector2d>& blocks, int particleCount) {
  const int m = rows.size();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(m, 2 * particleCount);
  for (int k = 0; k < m; ++k)
    for (int e = rows.rowStart[k]; e < rows.rowStart[k + 1]; ++e)
      out.block<1, 2>(k, 2 * rows.entryParticle[e]) += blocks[e].transpose();
  return out;
}
}  // namespace

Eigen::MatrixXd ConstraintRows::denseJ(int particleCount) const { return dense(*this, J, particleCount); }
Eigen::MatrixXd ConstraintRows::denseJdot(int particleCount) const { return dense(*this, Jdot, particleCount); }

}  // namespace particles::linear

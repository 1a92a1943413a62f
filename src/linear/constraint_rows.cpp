#include "linear/constraint_rows.h"

#include <algorithm>

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
  // Local pointers: the stores through row would otherwise make the compiler
  // reload every array's address after each constraint.
  const int* start = rowStart.data();
  int* particle = entryParticle.data();
  Eigen::Vector2d *j = J.data(), *jdot = Jdot.data();
  double *c = C.data(), *cdot = Cdot.data();
  for (int k = 0; k < m; ++k) {
    const Constraint& constraint = *constraints[k];
    ConstraintRow row;
    row.J = j + start[k];
    row.Jdot = jdot + start[k];
    constraint.evaluate(s, row);
    c[k] = row.C;
    cdot[k] = row.Cdot;
    const int* named = constraint.particles().data();
    for (int e = start[k]; e < start[k + 1]; ++e, ++named) {
      changed |= particle[e] != *named;
      particle[e] = *named;
    }
  }
  return changed;
}

double ConstraintRows::rhsAndDiagonal(const Eigen::VectorXd& w, const Eigen::VectorXd& v, const Eigen::VectorXd& f,
                                      double stiffness, double damping, Eigen::VectorXd& b,
                                      Eigen::VectorXd& diagonal) const {
  const int m = size();
  b.resize(m);
  diagonal.resize(m);
  const int *start = rowStart.data(), *particle = entryParticle.data();
  const Eigen::Vector2d *j = J.data(), *jdot = Jdot.data();
  const double *wp = w.data(), *vp = v.data(), *fp = f.data(), *c = C.data(), *cdot = Cdot.data();
  double *bp = b.data(), *dp = diagonal.data();
  double largest = 0.0;
  for (int k = 0; k < m; ++k) {
    double jdotv = 0.0, jwq = 0.0, jwj = 0.0;  // J̇_k q̇, J_k W Q, Σ w_p |J_e|²
    for (int e = start[k]; e < start[k + 1]; ++e) {
      const int p = particle[e];
      const double jx = j[e].x(), jy = j[e].y();
      jdotv += jdot[e].x() * vp[2 * p] + jdot[e].y() * vp[2 * p + 1];
      jwq += wp[p] * (jx * fp[2 * p] + jy * fp[2 * p + 1]);
      jwj += wp[p] * (jx * jx + jy * jy);
    }
    bp[k] = constraintRhs(jdotv, jwq, c[k], cdot[k], stiffness, damping);
    dp[k] = jwj;
    largest = std::max(largest, jwj);
  }
  return largest;
}

void ConstraintRows::addJtTimes(const Eigen::VectorXd& lambda, Eigen::VectorXd& f) const {
  const int m = size();
  const int *start = rowStart.data(), *particle = entryParticle.data();
  const Eigen::Vector2d* j = J.data();
  const double* l = lambda.data();
  double* fp = f.data();
  for (int k = 0; k < m; ++k)
    for (int e = start[k]; e < start[k + 1]; ++e) {
      const int p = particle[e];
      fp[2 * p] += j[e].x() * l[k];
      fp[2 * p + 1] += j[e].y() * l[k];
    }
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

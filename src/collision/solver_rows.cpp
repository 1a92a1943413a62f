// What the contact solve's stages do with one row, and an island's
// constraints solved as one block (solver_rows.h).
#include "solver_rows.h"

#include <algorithm>
#include <cmath>

namespace particles::solve {

namespace {
Eigen::Vector2d tangentOf(const Eigen::Vector2d& n) { return {-n.y(), n.x()}; }
constexpr double kRegularisation = 1e-10;
}  // namespace

double RowSystem::evaluateConstraint(Row& row, const Eigen::VectorXd& x) {
  const Constraint& constraint = *in->constraints[row.source];
  const std::vector<int>& ps = constraint.particles();
  jScratch.assign(ps.size(), Eigen::Vector2d::Zero());
  jdotScratch.assign(ps.size(), Eigen::Vector2d::Zero());
  ConstraintRow out{0.0, 0.0, jScratch.data(), jdotScratch.data()};
  constraint.evaluate(Phase{x, in->refs.v, in->mass, in->inverseMass}, out);
  double k = 0.0, norm2 = 0.0;
  for (std::size_t b = 0; b < ps.size(); ++b) {
    blocks[row.first + b] = {ps[b], jScratch[b]};
    k += in->inverseMass[ps[b]] * jScratch[b].squaredNorm();
    norm2 += jScratch[b].squaredNorm();
  }
  row.invK = k > 0.0 ? 1.0 / k : 0.0;
  row.norm = std::sqrt(norm2);
  return out.C;
}

double RowSystem::evaluateContact(int normalRow, const Eigen::VectorXd& x) {
  const double gap = (*contacts)[rows[normalRow].source].evaluate(x);
  setContactBlocks(normalRow);
  return gap;
}

void RowSystem::setContactBlocks(int normalRow) {
  Row& normal = rows[normalRow];
  const Contact& c = (*contacts)[normal.source];
  const Eigen::VectorXd& w = in->inverseMass;
  double k = 0.0;
  for (int b = 0; b < c.count(); ++b) {
    blocks[normal.first + b] = {c.particle[b], c.beta[b] * c.normal};
    k += w[c.particle[b]] * c.beta[b] * c.beta[b];
  }
  normal.invK = k > 0.0 ? 1.0 / k : 0.0;
  normal.norm = 1.0;
  if (normal.friction >= 0) {
    Row& friction = rows[normal.friction];
    const Eigen::Vector2d t = tangentOf(c.normal);
    for (int b = 0; b < c.count(); ++b) blocks[friction.first + b] = {c.particle[b], c.beta[b] * t};
    friction.invK = normal.invK;
  }
}

void RowSystem::move(const Row& row, double amount, Eigen::VectorXd& x) const {
  const Eigen::VectorXd& w = in->inverseMass;
  for (int b = row.first; b < row.first + row.count; ++b) {
    const int p = blocks[b].particle;
    x.segment<2>(2 * p) += (w[p] * amount) * blocks[b].J;
  }
}

double RowSystem::velocityOf(const Row& row, const Eigen::VectorXd& v) const {
  double jv = 0.0;
  for (int b = row.first; b < row.first + row.count; ++b) jv += blocks[b].J.dot(v.segment<2>(2 * blocks[b].particle));
  return jv;
}

double RowSystem::frictionBound(const Row& row) const {
  return (*contacts)[row.source].friction * rows[row.normal].lambda;
}

bool DirectBlock::factor(const RowSystem& R) {
  const Eigen::VectorXd& w = R.in->inverseMass;
  const int m = static_cast<int>(rows_.size());
  entries_.clear();
  for (int a = 0; a < m; ++a) {
    const Row& row = R.rows[rows_[a]];
    for (int b = row.first; b < row.first + row.count; ++b) entries_.push_back({R.blocks[b].particle, a, b});
  }
  std::sort(entries_.begin(), entries_.end());
  triplets_.clear();
  for (std::size_t g = 0; g < entries_.size();) {
    std::size_t end = g;
    while (end < entries_.size() && entries_[end][0] == entries_[g][0]) ++end;
    const double wp = w[entries_[g][0]];
    if (wp > 0.0)
      for (std::size_t i = g; i < end; ++i)
        for (std::size_t j = g; j < end; ++j) {
          const int bi = entries_[i][2], bj = entries_[j][2];
          triplets_.emplace_back(entries_[i][1], entries_[j][1], wp * R.blocks[bi].J.dot(R.blocks[bj].J));
        }
    g = end;
  }
  double scale = 0.0;
  for (const Eigen::Triplet<double>& t : triplets_)
    if (t.row() == t.col()) scale = std::max(scale, std::abs(t.value()));
  for (int a = 0; a < m; ++a) triplets_.emplace_back(a, a, kRegularisation * (scale > 0.0 ? scale : 1.0));
  K_.resize(m, m);
  K_.setFromTriplets(triplets_.begin(), triplets_.end());
  lu_.compute(K_);
  return lu_.info() == Eigen::Success;
}

bool DirectBlock::factorVelocities(const RowSystem& R) { return !rows_.empty() && factor(R); }

double DirectBlock::solveVelocities(RowSystem& R, Eigen::VectorXd& v) {
  const int m = static_cast<int>(rows_.size());
  rhs_.resize(m);
  double largest = 0.0;
  for (int a = 0; a < m; ++a) {
    const Row& row = R.rows[rows_[a]];
    rhs_[a] = row.target - R.velocityOf(row, v);
    if (row.norm > 0.0) largest = std::max(largest, std::abs(rhs_[a]) / row.norm);
  }
  delta_ = lu_.solve(rhs_);
  if (!delta_.allFinite()) return largest;
  for (int a = 0; a < m; ++a) {
    Row& row = R.rows[rows_[a]];
    row.lambda += delta_[a];
    R.move(row, delta_[a], v);
  }
  return largest;
}

double DirectBlock::projectPositions(RowSystem& R, Eigen::VectorXd& x) {
  const int m = static_cast<int>(rows_.size());
  rhs_.resize(m);
  double worst = 0.0;
  for (int a = 0; a < m; ++a) {
    Row& row = R.rows[rows_[a]];
    const double C = R.evaluateConstraint(row, x);
    rhs_[a] = -C;
    if (row.norm > 0.0) worst = std::max(worst, std::abs(C) / row.norm);
  }
  if (!factor(R)) return worst;
  delta_ = lu_.solve(rhs_);
  if (!delta_.allFinite()) return worst;
  for (int a = 0; a < m; ++a) R.move(R.rows[rows_[a]], delta_[a], x);
  return worst;
}

}  // namespace particles::solve

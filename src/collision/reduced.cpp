// Projected Gauss–Seidel on an island's contact rows with its constraints
// eliminated (solver_rows.h, relaxReduced).
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver_rows.h"
#include "particles/cancel.h"

namespace particles::solve {

namespace {

// G = J_c W J_bᵀ and L = J_c W J_cᵀ, from the blocks that share a particle.
void couplings(const RowSystem& R, const std::vector<int>& contactRows, const std::vector<int>& constraintRows,
               Eigen::MatrixXd& G, Eigen::MatrixXd& L) {
  const Eigen::VectorXd& w = R.in->inverseMass;
  // (particle, place, block, is a constraint), grouped by particle.
  std::vector<std::array<int, 4>> entries;
  auto add = [&](const std::vector<int>& rows, int kind) {
    for (int a = 0; a < static_cast<int>(rows.size()); ++a) {
      const Row& row = R.rows[rows[a]];
      for (int b = row.first; b < row.first + row.count; ++b) entries.push_back({R.blocks[b].particle, a, b, kind});
    }
  };
  add(contactRows, 0);
  add(constraintRows, 1);
  std::sort(entries.begin(), entries.end());
  G.setZero(static_cast<Eigen::Index>(contactRows.size()), static_cast<Eigen::Index>(constraintRows.size()));
  L.setZero(static_cast<Eigen::Index>(contactRows.size()), static_cast<Eigen::Index>(contactRows.size()));
  for (std::size_t g = 0; g < entries.size();) {
    std::size_t end = g;
    while (end < entries.size() && entries[end][0] == entries[g][0]) ++end;
    const double wp = w[entries[g][0]];
    if (wp > 0.0)
      for (std::size_t i = g; i < end; ++i) {
        if (entries[i][3] != 0) continue;
        for (std::size_t j = g; j < end; ++j) {
          const double product = wp * R.blocks[entries[i][2]].J.dot(R.blocks[entries[j][2]].J);
          (entries[j][3] == 0 ? L(entries[i][1], entries[j][1]) : G(entries[i][1], entries[j][1])) += product;
        }
      }
    g = end;
  }
}

}  // namespace

Relaxed relaxReduced(RowSystem& R, const std::vector<int>& contactRows, DirectBlock& block,
                     const ContactSettings& settings, Eigen::VectorXd& v) {
  Relaxed relaxed;
  if (!block.factorVelocities(R)) return relaxVelocities(R, contactRows, block, settings, v);
  block.solveVelocities(R, v);  // the constraints hold from the start
  const int m = static_cast<int>(contactRows.size());
  Eigen::MatrixXd G, S;
  couplings(R, contactRows, block.rows(), G, S);
  if (G.cols() > 0) S.noalias() -= G * block.solveColumns(G.transpose());
  Eigen::VectorXd jv(m), change = Eigen::VectorXd::Zero(m);
  for (int a = 0; a < m; ++a) jv[a] = R.velocityOf(R.rows[contactRows[a]], v);
  while (relaxed.passes < settings.coupledIterations && !cancelRequested()) {
    ++relaxed.passes;
    double largest = 0.0;
    for (const RowKind kind : {RowKind::Friction, RowKind::Normal})
      for (int a = 0; a < m; ++a) {
        Row& row = R.rows[contactRows[a]];
        if (row.kind != kind || !(S(a, a) > 0.0)) continue;
        double lo = 0.0, hi = std::numeric_limits<double>::infinity();
        if (kind == RowKind::Friction) hi = R.frictionBound(row), lo = -hi;
        const double next = std::clamp(row.lambda + (row.target - jv[a]) / S(a, a), lo, hi);
        const double impulse = next - row.lambda;
        if (impulse == 0.0) continue;
        row.lambda = next;
        change[a] += impulse;
        jv.noalias() += S.col(a) * impulse;
        largest = std::max(largest, std::abs(impulse) * S(a, a));
      }
    relaxed.largest = largest;
    if (!(largest > settings.coupledTolerance)) break;
  }
  // The impulses into the velocities, and the constraints' answer to them.
  for (int a = 0; a < m; ++a) R.move(R.rows[contactRows[a]], change[a], v);
  block.solveVelocities(R, v);
  return relaxed;
}

}  // namespace particles::solve

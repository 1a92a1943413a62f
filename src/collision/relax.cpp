// Block Gauss–Seidel over an island's rows, and the projection
// (solver_rows.h). Friction before the normals in each sweep, so that the
// unilateral rows have the last word.
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver_rows.h"
#include "particles/cancel.h"

namespace particles::solve {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// One projected Gauss–Seidel update of a contact row; returns |Δ(J v)|.
double relaxRow(RowSystem& R, Row& row, Eigen::VectorXd& v) {
  if (row.invK == 0.0) return 0.0;
  double lo = 0.0, hi = kInfinity;
  if (row.kind == RowKind::Friction) hi = R.frictionBound(row), lo = -hi;
  const double next = std::clamp(row.lambda + (row.target - R.velocityOf(row, v)) * row.invK, lo, hi);
  const double impulse = next - row.lambda;
  if (impulse == 0.0) return 0.0;
  row.lambda = next;
  R.move(row, impulse, v);
  return std::abs(impulse) / row.invK;
}
}  // namespace

Relaxed relaxVelocities(RowSystem& R, const std::vector<int>& contactRows, DirectBlock& block,
                        const ContactSettings& settings, Eigen::VectorXd& v) {
  Relaxed relaxed;
  const bool constraints = block.factorVelocities(R);
  while (relaxed.passes < settings.coupledIterations && !cancelRequested()) {
    ++relaxed.passes;
    double largest = constraints ? block.solveVelocities(R, v) : 0.0;
    for (const RowKind kind : {RowKind::Friction, RowKind::Normal})
      for (const int r : contactRows)
        if (R.rows[r].kind == kind) largest = std::max(largest, relaxRow(R, R.rows[r], v));
    relaxed.largest = largest;
    if (!(largest > settings.coupledTolerance)) break;
  }
  return relaxed;
}

Relaxed projectPositions(RowSystem& R, const std::vector<int>& contactRows, DirectBlock& block,
                         const ContactSettings& settings, Eigen::VectorXd& x) {
  Relaxed projected;
  for (const int r : contactRows) R.rows[r].mu = 0.0;
  while (projected.passes < settings.positionIterations && !cancelRequested()) {
    ++projected.passes;
    double worst = block.empty() ? 0.0 : block.projectPositions(R, x);
    for (const int r : contactRows) {
      Row& row = R.rows[r];
      if (row.kind != RowKind::Normal) continue;
      const double gap = (*R.contacts)[row.source].linearGap(x);  // along the solve's normal, as Box2D keeps it
      worst = std::max(worst, -gap);
      if (row.invK == 0.0) continue;
      // A push accumulates (μ ≥ 0): a row pulls back only what it pushed.
      const double amount = std::max(0.0, row.mu - gap * row.invK) - row.mu;
      if (amount == 0.0) continue;
      row.mu += amount;
      R.move(row, amount, x);
    }
    projected.largest = worst;
    if (!(worst > settings.slop)) break;
  }
  return projected;
}

}  // namespace particles::solve

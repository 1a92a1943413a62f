#include "xpbd/constraint_projection.h"

#include "particles/phase.h"

namespace particles {

void projectConstraint(const Constraint& constraint, const Eigen::VectorXd& v,
                       const Eigen::VectorXd& mass, const Eigen::VectorXd& inverseMass,
                       Eigen::VectorXd& x, std::vector<Eigen::Vector2d>& blocks) {
  const std::vector<int>& p = constraint.particles();
  const std::size_t n = p.size();
  if (blocks.size() < 2 * n) blocks.resize(2 * n);
  ConstraintRow row;
  row.J = blocks.data();
  row.Jdot = blocks.data() + n;
  constraint.evaluate(Phase{x, v, mass, inverseMass}, row);
  double weight = 0.0;
  for (std::size_t k = 0; k < n; ++k) weight += inverseMass[p[k]] * row.J[k].squaredNorm();
  if (weight == 0.0) return;  // pinned particles only, or no direction
  const double dl = multiplierStep(row.C, 0.0, Compliance{}, 0.0, 1.0 / weight);
  for (std::size_t k = 0; k < n; ++k) x.segment<2>(2 * p[k]) += (inverseMass[p[k]] * dl) * row.J[k];
}

}  // namespace particles

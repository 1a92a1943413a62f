#include "constraints/rod_chain.h"

#include <algorithm>
#include <limits>

namespace particles {

bool RodChain::build(const ConstraintList& constraints) {
  links_.clear();
  std::vector<Link> links;
  links.reserve(constraints.size());
  for (const auto& constraint : constraints) {
    const auto* rod = dynamic_cast<const RodConstraint*>(constraint.get());
    if (rod == nullptr) return false;
    links.push_back({rod, rod->particles()[0], rod->particles()[1], 0, {0, 0}, {0, 0}});
  }
  for (std::size_t k = 0; k + 1 < links.size(); ++k) {
    Link& link = links[k];
    const int mine[2] = {link.i, link.j}, next[2] = {links[k + 1].i, links[k + 1].j};
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c)
        if (mine[a] == next[c]) {
          link.mine[link.shared] = a;
          link.next[link.shared] = c;
          ++link.shared;
        }
  }
  links_ = std::move(links);
  return true;
}

RodChain::Formed RodChain::form(const Phase& s, const ConstraintList& constraints, const Eigen::VectorXd& f,
                                double stiffness, double damping, const Output& out) const {
  using Point = Eigen::Map<const Eigen::Vector2d>;
  const int m = static_cast<int>(links_.size());
  if (static_cast<int>(constraints.size()) != m || out.rows.size() != m) return {};
  const std::size_t bands = static_cast<std::size_t>(std::max(m - 1, 0));
  out.b.resize(m);
  out.diagonal.resize(m);
  out.bandDiagonal.resize(static_cast<std::size_t>(m));
  out.upper.resize(bands);
  out.tridiagonal.start(static_cast<std::size_t>(m));
  Eigen::Vector2d *J = out.rows.J.data(), *Jdot = out.rows.Jdot.data();
  double *C = out.rows.C.data(), *Cdot = out.rows.Cdot.data();
  double *b = out.b.data(), *diagonal = out.diagonal.data(), *band = out.bandDiagonal.data(), *upper = out.upper.data();
  const double *w = s.inverseMass.data(), *x = s.x.data(), *v = s.v.data(), *q = f.data();
  Formed formed{true, 0.0, std::numeric_limits<double>::infinity()};
  const Link* links = links_.data();
  const std::unique_ptr<Constraint>* listed = constraints.data();
  for (int k = 0; k < m; ++k) {
    const Link& link = links[k];
    const RodConstraint& rod = *link.rod;
    // The solver's list only grows (ParticleSystem::addConstraint), and a
    // rod's particles never change; the check costs a few loads a rod.
    if (listed[k].get() != &rod || rod.particles()[0] != link.i || rod.particles()[1] != link.j) return {};
    const int i = link.i, j = link.j;
    const Point vi(v + 2 * i), vj(v + 2 * j), qi(q + 2 * i), qj(q + 2 * j);
    const ConstraintKernel<2> kernel = rodKernel(rod.form(), Point(x + 2 * i), Point(x + 2 * j), vi, vj, rod.length());
    const double jdotv = kernel.Jdot[0].dot(vi) + kernel.Jdot[1].dot(vj);
    const double jwq = w[i] * kernel.J[0].dot(qi) + w[j] * kernel.J[1].dot(qj);
    b[k] = linear::constraintRhs(jdotv, jwq, kernel.C, kernel.Cdot, stiffness, damping);
    const double jwj = w[i] * kernel.J[0].squaredNorm() + w[j] * kernel.J[1].squaredNorm();
    diagonal[k] = band[k] = jwj;
    formed.largest = std::max(formed.largest, jwj);
    formed.smallest = std::min(formed.smallest, jwj);
    C[k] = kernel.C;
    Cdot[k] = kernel.Cdot;
    for (int n = 0; n < 2; ++n) {
      J[2 * k + n] = kernel.J[n];
      Jdot[2 * k + n] = kernel.Jdot[n];
    }
    double sum = 0.0;  // (J W Jᵀ)_{k−1,k}
    if (k > 0) {
      const Link& before = links[k - 1];
      for (int n = 0; n < before.shared; ++n) {
        const int p = before.mine[n] == 0 ? before.i : before.j;
        sum += w[p] * J[2 * (k - 1) + before.mine[n]].dot(J[2 * k + before.next[n]]);
      }
      upper[k - 1] = sum;
    }
    out.tridiagonal.row(static_cast<std::size_t>(k), jwj, sum, b[k]);
  }
  return formed;
}

void RodChain::addJtTimes(const linear::ConstraintRows& rows, const Eigen::VectorXd& lambda, Eigen::VectorXd& f) const {
  // Local pointers and values read before the stores: f may alias nothing
  // here, but the compiler cannot know it and would reload them.
  const Link* links = links_.data();
  const Eigen::Vector2d* J = rows.J.data();
  const double* l = lambda.data();
  double* q = f.data();
  const int m = static_cast<int>(links_.size());
  for (int k = 0; k < m; ++k) {
    const int i = links[k].i, j = links[k].j;
    const Eigen::Vector2d atI = J[2 * k] * l[k], atJ = J[2 * k + 1] * l[k];
    q[2 * i] += atI.x();
    q[2 * i + 1] += atI.y();
    q[2 * j] += atJ.x();
    q[2 * j + 1] += atJ.y();
  }
}

}  // namespace particles

#include "particles/constraints/rod.h"

#include "particles/check.h"

namespace particles {

ConstraintKernel<2> rodKernel(RodForm form, const Eigen::Vector2d& xi, const Eigen::Vector2d& xj,
                              const Eigen::Vector2d& vi, const Eigen::Vector2d& vj, double length) {
  const Eigen::Vector2d d = xi - xj, ddot = vi - vj;
  ConstraintKernel<2> k;
  if (form == RodForm::Squared) {
    k.C = d.squaredNorm() - length * length;
    k.Cdot = 2.0 * d.dot(ddot);
    k.J[0] = 2.0 * d;
    k.Jdot[0] = 2.0 * ddot;
  } else {
    const double l = d.norm();
    if (l == 0.0) {  // coincident ends: no direction to push along
      k.C = -length;
      k.Cdot = 0.0;
      k.J[0].setZero();
      k.Jdot[0].setZero();
    } else {
      const Eigen::Vector2d u = d / l;
      const double rate = u.dot(ddot);  // d·ḋ/|d|
      k.C = l - length;
      k.Cdot = rate;
      k.J[0] = u;
      k.Jdot[0] = (ddot - u * rate) / l;  // ḋ/|d| − d (d·ḋ)/|d|³
    }
  }
  k.J[1] = -k.J[0];
  k.Jdot[1] = -k.Jdot[0];
  return k;
}

const char* rodFormName(RodForm form) { return form == RodForm::Squared ? "squared" : "root"; }

RodForm parseRodForm(const std::string& name) {
  if (name == "squared") return RodForm::Squared;
  if (name == "root") return RodForm::Root;
  throw std::invalid_argument("rod form must be 'squared' or 'root', got '" + name + "'");
}

RodConstraint::RodConstraint(int i, int j, double length, RodForm form)
    : Constraint({i, j}), length_(length), form_(form) {
  requirePositive("rod length", length);
  if (i == j) throw std::invalid_argument("rod joins particle " + std::to_string(i) + " to itself");
}

void RodConstraint::evaluate(const Phase& s, ConstraintRow& row) const {
  const int i = particles()[0], j = particles()[1];
  const ConstraintKernel<2> k =
      rodKernel(form_, s.position(i), s.position(j), s.velocity(i), s.velocity(j), length_);
  row.C = k.C;
  row.Cdot = k.Cdot;
  for (int n = 0; n < 2; ++n) {
    row.J[n] = k.J[n];
    row.Jdot[n] = k.Jdot[n];
  }
}

double RodConstraint::violation(const Phase& s) const {
  return std::abs((s.position(particles()[0]) - s.position(particles()[1])).norm() - length_);
}

void RodConstraint::sketch(const Phase& s, Sketch& out) const {
  out.lines.push_back({s.position(particles()[0]), s.position(particles()[1])});
}

}  // namespace particles

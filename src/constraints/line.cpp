#include "particles/constraints/line.h"

#include <cmath>

#include "particles/check.h"

namespace particles {

ConstraintKernel<1> lineKernel(const Eigen::Vector2d& x, const Eigen::Vector2d& v,
                               const Eigen::Vector2d& point, double angle) {
  const Eigen::Vector2d n(-std::sin(angle), std::cos(angle));
  ConstraintKernel<1> k;
  k.C = n.dot(x - point);
  k.Cdot = n.dot(v);
  k.J[0] = n;
  k.Jdot[0].setZero();
  return k;
}

LineConstraint::LineConstraint(int particle, const Eigen::Vector2d& point, double angle)
    : Constraint({particle}), point_(point), angle_(angle) {
  requireFinite("line point.x", point.x());
  requireFinite("line point.y", point.y());
  requireFinite("line angle", angle);
}

void LineConstraint::evaluate(const Phase& s, ConstraintRow& row) const {
  const int i = particles()[0];
  const ConstraintKernel<1> k = lineKernel(s.position(i), s.velocity(i), point_, angle_);
  row.C = k.C;
  row.Cdot = k.Cdot;
  row.J[0] = k.J[0];
  row.Jdot[0] = k.Jdot[0];
}

double LineConstraint::violation(const Phase& s) const {
  return std::abs(lineKernel(s.position(particles()[0]), Eigen::Vector2d::Zero(), point_, angle_).C);
}

void LineConstraint::sketch(const Phase&, Sketch& out) const {
  // A long segment through the point; the view clips it.
  const Eigen::Vector2d u(std::cos(angle_), std::sin(angle_));
  out.lines.push_back({point_ - 100.0 * u, point_ + 100.0 * u});
}

}  // namespace particles

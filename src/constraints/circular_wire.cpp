#include "particles/constraints/circular_wire.h"

#include "particles/check.h"

namespace particles {

ConstraintKernel<1> circularWireKernel(const Eigen::Vector2d& x, const Eigen::Vector2d& v,
                                       const Eigen::Vector2d& centre, double radius) {
  const Eigen::Vector2d d = x - centre;
  ConstraintKernel<1> k;
  k.C = d.squaredNorm() - radius * radius;
  k.Cdot = 2.0 * d.dot(v);
  k.J[0] = 2.0 * d;
  k.Jdot[0] = 2.0 * v;
  return k;
}

CircularWireConstraint::CircularWireConstraint(int particle, const Eigen::Vector2d& centre,
                                               double radius)
    : Constraint({particle}), centre_(centre), radius_(radius) {
  requireFinite("wire centre.x", centre.x());
  requireFinite("wire centre.y", centre.y());
  requirePositive("wire radius", radius);
}

void CircularWireConstraint::evaluate(const Phase& s, ConstraintRow& row) const {
  const int i = particles()[0];
  const ConstraintKernel<1> k = circularWireKernel(s.position(i), s.velocity(i), centre_, radius_);
  row.C = k.C;
  row.Cdot = k.Cdot;
  row.J[0] = k.J[0];
  row.Jdot[0] = k.Jdot[0];
}

double CircularWireConstraint::violation(const Phase& s) const {
  return std::abs((s.position(particles()[0]) - centre_).norm() - radius_);
}

void CircularWireConstraint::sketch(const Phase&, Sketch& out) const {
  out.circles.push_back({centre_, radius_});
}

}  // namespace particles

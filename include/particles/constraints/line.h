#pragma once
#include "particles/constraint.h"

namespace particles {

// Particle on the straight line through point p with direction (cos α, sin α),
// α counter-clockwise from +x. With unit normal n = (−sin α, cos α):
//   C = n·(x − p),   Ċ = n·v,   J = n,   J̇ = 0.
// (The seed report writes C = sin α·x + cos α·y + c, which measures α clockwise;
// both give the horizontal line for α = 0.)
ConstraintKernel<1> lineKernel(const Eigen::Vector2d& x, const Eigen::Vector2d& v,
                               const Eigen::Vector2d& point, double angle);

class LineConstraint : public Constraint {
 public:
  LineConstraint(int particle, const Eigen::Vector2d& point, double angle);

  const char* type() const override { return "line"; }
  void evaluate(const Phase& s, ConstraintRow& row) const override;
  double violation(const Phase& s) const override;
  double lengthScale() const override { return 0.0; }
  void sketch(const Phase& s, Sketch& out) const override;

  const Eigen::Vector2d& point() const { return point_; }
  double angle() const { return angle_; }

 private:
  Eigen::Vector2d point_;
  double angle_;  // radians
};

}  // namespace particles

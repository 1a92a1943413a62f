#pragma once
#include "particles/constraint.h"

namespace particles {

// Bead on a circular wire of radius r about a fixed centre c, with d = x − c:
//   C = d·d − r²,   Ċ = 2 d·v,   J = 2d,   J̇ = 2v.
ConstraintKernel<1> circularWireKernel(const Eigen::Vector2d& x, const Eigen::Vector2d& v,
                                       const Eigen::Vector2d& centre, double radius);

class CircularWireConstraint : public Constraint {
 public:
  CircularWireConstraint(int particle, const Eigen::Vector2d& centre, double radius);

  const char* type() const override { return "circular-wire"; }
  void evaluate(const Phase& s, ConstraintRow& row) const override;
  double violation(const Phase& s) const override;
  double lengthScale() const override { return radius_; }
  void sketch(const Phase& s, Sketch& out) const override;

  const Eigen::Vector2d& centre() const { return centre_; }
  double radius() const { return radius_; }

 private:
  Eigen::Vector2d centre_;
  double radius_;  // world units
};

}  // namespace particles

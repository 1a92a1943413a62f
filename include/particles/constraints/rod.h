#pragma once
#include <string>

#include "particles/constraint.h"

namespace particles {

// Rod of length r between particles i and j, with d = x_i − x_j, ḋ = v_i − v_j.
enum class RodForm {
  // C = d·d − r²,  Ċ = 2 d·ḋ,  J = (2d, −2d),  J̇ = (2ḋ, −2ḋ).
  Squared,
  // C = |d| − r,  Ċ = d·ḋ/|d|,  J = (d/|d|, −d/|d|),
  // J̇ = (ḋ/|d| − d (d·ḋ)/|d|³, −that). The seed report's J̇ leaves out the
  // second term; the finite-difference test of J̇ catches it.
  Root,
};

// Inline, so that a pass over many rods (the constraint solve's chain of rods,
// src/constraints/rod_chain.h) computes each rod's rows without a call.
inline ConstraintKernel<2> rodKernel(RodForm form, const Eigen::Vector2d& xi, const Eigen::Vector2d& xj,
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

const char* rodFormName(RodForm form);   // "squared" | "root"
RodForm parseRodForm(const std::string& name);  // throws on anything else

class RodConstraint : public Constraint {
 public:
  RodConstraint(int i, int j, double length, RodForm form = RodForm::Squared);

  const char* type() const override { return "rod"; }
  void evaluate(const Phase& s, ConstraintRow& row) const override;
  double violation(const Phase& s) const override;
  double lengthScale() const override { return length_; }
  void sketch(const Phase& s, Sketch& out) const override;

  double length() const { return length_; }
  RodForm form() const { return form_; }

 private:
  double length_;  // world units
  RodForm form_;
};

}  // namespace particles

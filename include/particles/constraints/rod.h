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

ConstraintKernel<2> rodKernel(RodForm form, const Eigen::Vector2d& xi, const Eigen::Vector2d& xj,
                              const Eigen::Vector2d& vi, const Eigen::Vector2d& vj, double length);

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

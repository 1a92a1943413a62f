#include "particles/constraints/rod.h"

#include "particles/check.h"

namespace particles {

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

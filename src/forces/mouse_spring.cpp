#include "particles/forces/mouse_spring.h"

#include "particles/check.h"
#include "particles/constants.h"

#include <cmath>
#include <string>

namespace particles {

MouseSpringForce::MouseSpringForce(int i, const Eigen::Vector2d& target, double stiffness,
                                   double damping)
    : i_(i), target_(target), stiffness_(stiffness), damping_(damping) {
  requireFinite("mouse target.x", target.x());
  requireFinite("mouse target.y", target.y());
  requireNonNegative("mouse spring stiffness", stiffness);
  requireNonNegative("mouse spring damping", damping);
}

void MouseSpringForce::apply(const Phase& s, Eigen::VectorXd& f) const {
  f.segment<2>(2 * i_) -= stiffness_ * (s.position(i_) - target_) + damping_ * s.velocity(i_);
}

double MouseSpringForce::potential(const Phase& s) const {
  return 0.5 * stiffness_ * (s.position(i_) - target_).squaredNorm();
}

void MouseSpringForce::addJacobians(const Phase&, Triplets& dfdx, Triplets& dfdv) const {
  for (int r = 0; r < 2; ++r) {
    dfdx.emplace_back(2 * i_ + r, 2 * i_ + r, -stiffness_);
    dfdv.emplace_back(2 * i_ + r, 2 * i_ + r, -damping_);
  }
}

void MouseSpringForce::sketch(const Phase& s, Sketch& out) const {
  out.lines.push_back({s.position(i_), target_});
}

}  // namespace particles

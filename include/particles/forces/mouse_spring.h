#pragma once
#include "particles/force.h"

namespace particles {

// The user's hand: a damped spring from a particle to the cursor, its gains
// chosen when it grabs (particles/grab.h).
// One-sided spring of rest length 0 pulling particle i toward a target point
// that the user moves: f_i = −k_s (x_i − t) − k_d v_i,  E = ½ k_s |x_i − t|².
// Nothing reacts on the target. A damping of 2√(k_s m) is critical for mass m.
// xpbd holds it as a compliant attachment (xpbd/attachment.h).
class MouseSpringForce : public Force {
 public:
  MouseSpringForce(int i, const Eigen::Vector2d& target, double stiffness, double damping);

  const char* type() const override { return "mouse-spring"; }
  void apply(const Phase& s, Eigen::VectorXd& f) const override;
  bool hasPotential() const override { return true; }
  double potential(const Phase& s) const override;
  std::vector<int> particles() const override { return {i_}; }
  bool hasJacobians() const override { return true; }
  void addJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  void sketch(const Phase& s, Sketch& out) const override;

  int particle() const { return i_; }
  const Eigen::Vector2d& target() const { return target_; }
  void setTarget(const Eigen::Vector2d& target) { target_ = target; }
  double stiffness() const { return stiffness_; }
  double damping() const { return damping_; }

 private:
  int i_;
  Eigen::Vector2d target_;
  double stiffness_;  // k_s, force / length
  double damping_;    // k_d, force / speed
};

}  // namespace particles

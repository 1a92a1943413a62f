#pragma once
#include "particles/force.h"

namespace particles {

// The user's hand as a soft joint, after Box2D's mouse joint: its stiffness is
// a frequency and a damping ratio, scaled by the grabbed mass m so that every
// particle follows the cursor alike, however heavy:
//   ω = 2π f,   k_s = m ω²,   k_d = 2 m ζ ω.
struct MouseJointSettings {
  double frequency = 5.0;     // f, Hz: how briskly the particle follows
  double dampingRatio = 0.7;  // ζ, non-dimensional: 1 is critical
};
struct MouseSpringGains {
  double stiffness;  // k_s, force / length
  double damping;    // k_d, force / speed
};
// Throws std::invalid_argument naming the value when the mass, frequency or
// ratio is not finite and positive (ratio ≥ 0), or when k_s or k_d overflows
// (a mass near 1e306 would make them infinite).
MouseSpringGains mouseSpringGains(double mass, const MouseJointSettings& joint);

// One-sided spring of rest length 0 pulling particle i toward a target point
// that the user moves: f_i = −k_s (x_i − t) − k_d v_i,  E = ½ k_s |x_i − t|².
// Nothing reacts on the target. A damping of 2√(k_s m) is critical for mass m.
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

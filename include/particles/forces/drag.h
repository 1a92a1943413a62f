#pragma once
#include "particles/force.h"

namespace particles {

// Viscous drag on every movable particle: f_i = −k_d v_i.
class DragForce : public Force {
 public:
  explicit DragForce(double damping);  // k_d, mass / s

  const char* type() const override { return "drag"; }
  void apply(const Phase& s, Eigen::VectorXd& f) const override;
  bool hasJacobians() const override { return true; }
  void addJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;

  double damping() const { return damping_; }

 private:
  double damping_;
};

}  // namespace particles

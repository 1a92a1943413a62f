#pragma once
#include "particles/force.h"

namespace particles {

// Uniform gravity on every movable particle: f_i = m_i g,  E = −Σ m_i g·x_i.
class GravityForce : public Force {
 public:
  explicit GravityForce(const Eigen::Vector2d& g);  // world units / s²

  const char* type() const override { return "gravity"; }
  void apply(const Phase& s, Eigen::VectorXd& f) const override;
  bool hasPotential() const override { return true; }
  double potential(const Phase& s) const override;
  bool hasJacobians() const override { return true; }
  void addJacobians(const Phase&, Triplets&, Triplets&) const override {}

  const Eigen::Vector2d& acceleration() const { return g_; }

 private:
  Eigen::Vector2d g_;
};

}  // namespace particles

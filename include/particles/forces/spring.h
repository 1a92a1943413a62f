#pragma once
#include "particles/force.h"

namespace particles {

// Damped spring between particles i and j, with l = x_i − x_j, l̇ = v_i − v_j:
//   f_i = −[k_s(|l| − r) + k_d (l̇·l)/|l|] l/|l|,   f_j = −f_i,
//   E = ½ k_s (|l| − r)².
// (The seed report prints the damping term as k_d l/|l|; the velocity term
// l̇·l/|l| above is the damped spring of Witkin & Baraff.)
Eigen::Vector2d springForce(const Eigen::Vector2d& l, const Eigen::Vector2d& ldot, double rest,
                            double stiffness, double damping);

// ∂f_i/∂l and ∂f_i/∂l̇ of springForce (2×2 blocks; ∂f_i/∂x_j = −∂f_i/∂x_i).
void springJacobian(const Eigen::Vector2d& l, const Eigen::Vector2d& ldot, double rest,
                    double stiffness, double damping, Eigen::Matrix2d& dfdl, Eigen::Matrix2d& dfdldot);

// The definite approximation for implicit solvers: ∂f/∂l ≈ −k_s u uᵀ −
// k_s max(0, 1 − r/|l|) P, symmetric negative semi-definite (the transverse
// term is dropped under compression, where it is positive and buckles the
// linear system, and so is the non-symmetric damping part); ∂f/∂l̇ exact.
void springDefiniteJacobian(const Eigen::Vector2d& l, double rest, double stiffness,
                            double damping, Eigen::Matrix2d& dfdl, Eigen::Matrix2d& dfdldot);

class SpringForce : public Force {
 public:
  SpringForce(int i, int j, double restLength, double stiffness, double damping);

  const char* type() const override { return "spring"; }
  void apply(const Phase& s, Eigen::VectorXd& f) const override;
  bool hasPotential() const override { return true; }
  double potential(const Phase& s) const override;
  std::vector<int> particles() const override { return {i_, j_}; }
  bool hasJacobians() const override { return true; }
  void addJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  void addDefiniteJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  void sketch(const Phase& s, Sketch& out) const override;
  bool dropLinks(const LinkSet& broken) override;

  int first() const { return i_; }
  int second() const { return j_; }
  double restLength() const { return rest_; }
  // Strain |x_j − x_i| / r − 1 at positions x (2n): > 0 stretched, < 0 compressed.
  double strain(const Eigen::VectorXd& x) const {
    return (x.segment<2>(2 * j_) - x.segment<2>(2 * i_)).norm() / rest_ - 1.0;
  }
  double stiffness() const { return stiffness_; }
  double damping() const { return damping_; }
  // A disabled spring (torn) adds no force, potential, Jacobian or line.
  // Torn by ParticleSystem::breakLinks, switched by ParticleSystem::
  // setSpringEnabled, both of which keep the system's spring batch in step.
  bool enabled() const { return enabled_; }

 private:
  void addBlocks(const Eigen::Matrix2d& dl, const Eigen::Matrix2d& dldot, Triplets& dfdx,
                 Triplets& dfdv) const;
  int i_, j_;
  double rest_;       // world units
  double stiffness_;  // k_s, force / length
  double damping_;    // k_d, force / speed
  bool enabled_ = true;
  friend class ParticleSystem;
};

}  // namespace particles

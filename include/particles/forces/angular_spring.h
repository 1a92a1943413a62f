#pragma once
#include <array>

#include "particles/force.h"

namespace particles {

// Angle spring on a triple (p1, p2, p3) with p2 the vertex. With arms
// a = x1 − x2 and b = x3 − x2 the signed angle is θ = atan2(a×b, a·b) and
//   E = ½ k_s (θ − θ₀)²,   f_k = −[k_s (θ − θ₀) + k_d θ̇] ∂θ/∂x_k,
//   ∂θ/∂x1 = (a_y, −a_x)/|a|²,  ∂θ/∂x3 = (−b_y, b_x)/|b|²,  ∂θ/∂x2 = −(∂θ/∂x1 + ∂θ/∂x3),
//   θ̇ = Σ_k ∂θ/∂x_k · v_k.
// θ is invariant under translation and rotation, so the three forces sum to
// zero and exert no net torque. (The seed report instead puts a spring between
// p1 and p3 whose rest length follows from the current arm lengths, with its
// reaction on p2: that force is not conservative and is not offered here.)
struct AngularSpringKernel {
  double angle;                            // θ, in (−π, π]
  double rate;                             // θ̇
  Eigen::Vector2d gradient[3];             // ∂θ/∂x1, ∂θ/∂x2, ∂θ/∂x3
};
AngularSpringKernel angularSpringKernel(const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                                        const Eigen::Vector2d& x3, const Eigen::Vector2d& v1,
                                        const Eigen::Vector2d& v2, const Eigen::Vector2d& v3);

// Force Jacobians of the angle spring, 6×6 over (x1, x2, x3). With g_k = ∂θ/∂x_k,
// τ = k_s (θ − θ₀) + k_d θ̇ and H_kl = ∂g_k/∂x_l (the Hessian of θ),
//   ∂f_k/∂x_l = −k_s g_k g_lᵀ − k_d g_k (Σ_j H_lj v_j)ᵀ − τ H_kl,   ∂f_k/∂v_l = −k_d g_k g_lᵀ.
// With R the rotation by −90° (R a = (a_y, −a_x)), â = a/|a|, b̂ = b/|b|:
//   G_a = R (I − 2 â âᵀ)/|a|²,  G_b = −R (I − 2 b̂ b̂ᵀ)/|b|²   (both symmetric),
//   H = [ G_a  −G_a  0 ;  −G_a  G_a+G_b  −G_b ;  0  −G_b  G_b ].
// definite = true keeps only the Gauss–Newton term −k_s g gᵀ of ∂f/∂x (symmetric
// negative semi-definite; the τ H term is indefinite and the damping term is
// not symmetric) for implicit solvers that need a definite matrix.
void angularSpringJacobian(const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                           const Eigen::Vector2d& x3, const Eigen::Vector2d& v1,
                           const Eigen::Vector2d& v2, const Eigen::Vector2d& v3, double restAngle,
                           double stiffness, double damping, bool definite,
                           Eigen::Matrix<double, 6, 6>& dfdx, Eigen::Matrix<double, 6, 6>& dfdv);

// θ − θ₀ wrapped into (−π, π].
double angleDifference(double angle, double restAngle);

class AngularSpringForce : public Force {
 public:
  AngularSpringForce(int p1, int p2, int p3, double restAngle, double stiffness, double damping);

  const char* type() const override { return "angular-spring"; }
  void apply(const Phase& s, Eigen::VectorXd& f) const override;
  bool hasPotential() const override { return true; }
  double potential(const Phase& s) const override;
  std::vector<int> particles() const override { return {p_[0], p_[1], p_[2]}; }
  bool hasJacobians() const override { return true; }
  void addJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  void addDefiniteJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  void sketch(const Phase& s, Sketch& out) const override;
  // A link that breaks under an arm (p1–p2 or p2–p3) takes the angle spring with it.
  bool dropLinks(const LinkSet& broken) override;

  const std::array<int, 3>& triple() const { return p_; }
  double restAngle() const { return restAngle_; }
  double stiffness() const { return stiffness_; }
  double damping() const { return damping_; }
  // A disabled angle spring (an arm torn) adds no force, potential, Jacobian or line.
  bool enabled() const { return enabled_; }

 private:
  void addJacobiansImpl(const Phase& s, bool definite, Triplets& dfdx, Triplets& dfdv) const;
  std::array<int, 3> p_;
  double restAngle_;  // θ₀, radians, signed (counter-clockwise from arm a to arm b)
  double stiffness_;  // k_s, energy / rad²
  double damping_;    // k_d, energy·s / rad²
  bool enabled_ = true;
  friend class ParticleSystem;
};

}  // namespace particles

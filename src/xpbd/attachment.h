#pragma once
// Compliant attachment: a particle held to a point by a damped spring of
// rest length 0 (the mouse joint, forces/mouse_spring.h) in position form.
#include <Eigen/Core>

#include "xpbd/multiplier.h"

namespace particles {

// Particle i held to the point t, one scalar constraint per axis r:
//   C_r = x_{i,r} − t_r,   ∇C_r = e_r,   ∇C_r W ∇C_rᵀ = w_i,
// with α = 1/k_s and β = k_d: the force f_i = −k_s (x_i − t) − k_d v_i
// (t still over the step). The constraint is linear, so one projection of
// each axis solves the substep's backward-Euler step of the joint exactly:
// stable at any k_s and k_d, which lets the joint be as stiff as the
// structure it pulls against.
struct CompliantAttachment {
  int i = 0;
  Eigen::Vector2d target = Eigen::Vector2d::Zero();
  Compliance compliance;
};

// One projection on the flat position arrays, as projectAngle; lambda holds
// the two axes' multipliers of this substep.
void projectAttachment(const CompliantAttachment& c, const Eigen::VectorXd& w, const Eigen::VectorXd& xn,
                       Eigen::VectorXd& x, Eigen::Vector2d& lambda);

}  // namespace particles

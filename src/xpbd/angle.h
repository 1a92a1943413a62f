#pragma once
// Compliant angle constraint: an angle spring in position form.
#include <Eigen/Core>

#include "xpbd/multiplier.h"

namespace particles {

// On the triple (p1, p2, p3), p2 the vertex, with θ and ∂θ/∂x_k from
// angularSpringKernel (forces/angular_spring.h):
//   C = θ − θ₀ (wrapped into (−π, π]),   ∇_k C = ∂θ/∂x_k,
// with α = 1/k_s (rad²/energy) and β = k_d: the angle spring
// f_k = −[k_s (θ − θ₀) + k_d θ̇] ∂θ/∂x_k.
struct CompliantAngle {
  int p[3] = {0, 0, 0};
  double restAngle = 0.0;  // θ₀, radians
  Compliance compliance;
};

// One projection on the flat position arrays, as projectDistance.
void projectAngle(const CompliantAngle& c, const Eigen::VectorXd& w, const Eigen::VectorXd& xn,
                  Eigen::VectorXd& x, double& lambda);

}  // namespace particles

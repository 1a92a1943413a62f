#include "xpbd/area.h"

#include <algorithm>

#include "particles/forces/polygon_area.h"

namespace particles {

void projectArea(const CompliantArea& c, const Eigen::VectorXd& w, Eigen::VectorXd& x, double& lambda) {
  if (lambda == 0.0 && ringArea(x, c.ring) >= c.floor * c.restArea) return;  // above its floor, never pushed
  std::vector<Eigen::Vector2d> gradient;  // ∂A/∂x_k; ∇_k C = ∂A/∂x_k / A₀
  const double C = ringAreaGradient(x, c.ring, gradient) / c.restArea - c.floor;
  const double weight = ringAreaWeight(gradient, c.ring, w) / (c.restArea * c.restArea);
  // λ ≥ 0: the floor pushes a face out, never pulls it in.
  const double dl = std::max(multiplierStep(C, 0.0, c.compliance, lambda, inverseDenominator(weight, c.compliance)),
                             -lambda);
  for (std::size_t k = 0; k < c.ring.size(); ++k)
    x.segment<2>(2 * c.ring[k]) += (w[c.ring[k]] * dl / c.restArea) * gradient[k];
  lambda += dl;
}

}  // namespace particles

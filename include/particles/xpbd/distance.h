#pragma once
// Compliant distance constraint: a damped spring in position form.
#include <cmath>

#include "particles/xpbd/multiplier.h"

namespace particles {

// Between particles i and j with d = x_i − x_j, u = d/|d|:
//   C = |d| − r,   ∇_i C = u,   ∇_j C = −u,   ∇C W ∇Cᵀ = w_i + w_j,
// and with compliance α = 1/k_s and damping β = k_d it is the spring
// f_i = −[k_s(|d| − r) + k_d ḋ·u] u of forces/spring.h.
// ∇C W ∇Cᵀ does not depend on x, so the denominator of Δλ is set once per
// step by prepareDistance.
struct CompliantDistance {
  int i = 0, j = 0;
  double rest = 0.0;  // r, world units
  Compliance compliance;
  double inverseDenominator = 0.0;  // 1/((1 + γ)(w_i + w_j) + α̃)
};

inline void prepareDistance(CompliantDistance& c, const double* w) {
  c.inverseDenominator = inverseDenominator(w[c.i] + w[c.j], c.compliance);
}

// One projection of the constraint on the flat position array x (x0, y0, x1, ...),
// given the positions xn at the start of the substep, the inverse masses w and the
// constraint's multiplier λ (updated in place); prepareDistance first.
inline void projectDistance(const CompliantDistance& c, const double* w, const double* xn,
                            double* x, double& lambda) {
  const int a = 2 * c.i, b = 2 * c.j;
  const double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1];
  const double length = std::sqrt(dx * dx + dy * dy);
  if (length == 0.0) return;  // no direction
  const double inverseLength = 1.0 / length;
  const double ux = dx * inverseLength, uy = dy * inverseLength;
  // ∇C·(x − xⁿ) = u·((x_i − xⁿ_i) − (x_j − xⁿ_j))
  const double displacement =
      ux * ((x[a] - xn[a]) - (x[b] - xn[b])) + uy * ((x[a + 1] - xn[a + 1]) - (x[b + 1] - xn[b + 1]));
  const double dl = multiplierStep(length - c.rest, displacement, c.compliance, lambda, c.inverseDenominator);
  lambda += dl;
  x[a] += w[c.i] * dl * ux;
  x[a + 1] += w[c.i] * dl * uy;
  x[b] -= w[c.j] * dl * ux;
  x[b + 1] -= w[c.j] * dl * uy;
}

}  // namespace particles

#pragma once
// The pressure of a gas shut inside a closed ring of particles (a soft
// body's outline): in 2D an area holding a fixed amount of an ideal gas at
// a fixed temperature, so that p A stays p₀ A₀ (Boyle's law). The gas pushes
// each corner outward along the area's gradient:
//   p(A) = p₀ A₀ / A,   E = −p₀ A₀ ln(A/A₀),   f_k = p(A) ∂A/∂x_k
// with A the ring's signed area (counter-clockwise positive,
// forces/polygon_area.h), A₀ > 0 the rest area and p₀ ≥ 0 the pressure
// there (force per length in 2D). Below a tenth of A₀ (a ring crushed flat or
// turned inside out) the pressure is held at its value there, 10 p₀, so the
// force stays finite and still pushes the ring open:
//   A < A₀/10:  p = 10 p₀,   E = p₀ A₀ ln 10 − 10 p₀ (A − A₀/10).
// Jacobians, with H the constant Hessian of A and p' = dp/dA (−p/A, or 0
// below A₀/10):
//   ∂f_k/∂x_l = p' ∂A/∂x_k ∂A/∂x_lᵀ + p H_kl,   ∂f/∂v = 0;
// the definite form keeps the first term (p' ≤ 0), dropping p H (indefinite).
// xpbd applies it in its prediction, as gravity: a load, which the springs'
// projections then balance exactly at rest. (Projected as an implicit step
// instead, one pass per substep would leave the balance off by the gas's own
// stiffness h² |p'| ∇A W ∇Aᵀ, a factor of 3 for a stiff gas at 60 Hz.)
#include <algorithm>
#include <vector>

#include "particles/force.h"

namespace particles {

// p(A) and dp/dA of the law above.
struct PressureLaw {
  double restArea;  // A₀ > 0
  double pressure;  // p₀ ≥ 0, at A₀
  static constexpr double kFloor = 0.1;  // the fraction of A₀ below which p is held
  double at(double area) const { return pressure * restArea / std::max(area, kFloor * restArea); }
  double slope(double area) const { return area > kFloor * restArea ? -at(area) / area : 0.0; }
  double energy(double area) const;
};

class PressureForce : public Force {
 public:
  // ring: at least three distinct particles, counter-clockwise; restArea > 0;
  // pressure ≥ 0. Throws std::invalid_argument naming the bad field.
  PressureForce(std::vector<int> ring, double restArea, double pressure);

  const char* type() const override { return "pressure"; }
  void apply(const Phase& s, Eigen::VectorXd& f) const override;
  bool hasPotential() const override { return true; }
  double potential(const Phase& s) const override;
  std::vector<int> particles() const override { return ring_; }
  bool hasJacobians() const override { return true; }
  void addJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  void addDefiniteJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  // A torn side lets the gas out: the force goes.
  bool dropLinks(const LinkSet& broken) override;
  // The ring's outline.
  void sketch(const Phase& s, Sketch& out) const override;

  const std::vector<int>& ring() const { return ring_; }
  const PressureLaw& law() const { return law_; }
  double restArea() const { return law_.restArea; }
  double pressure() const { return law_.pressure; }  // p₀
  bool enabled() const { return enabled_; }

 private:
  void addJacobiansImpl(const Phase& s, bool definite, Triplets& dfdx) const;
  std::vector<int> ring_;
  PressureLaw law_;
  bool enabled_ = true;
};

}  // namespace particles

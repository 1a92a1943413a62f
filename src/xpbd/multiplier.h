#pragma once
// The XPBD multiplier update shared by every position-level constraint
// (Macklin, Müller & Chentanez 2016, "XPBD: Position-Based Simulation of
// Compliant Constrained Dynamics", eqs. 18 and 26).
//
// For one scalar constraint C(x) with compliance α (= 1/k_s, length/force for a
// spring) and damping β (= k_d), over a substep h, with xⁿ the positions at the
// start of the substep and λ the multiplier accumulated so far in this substep:
//   α̃ = α/h²,   γ = α̃ β̃/h = α β/h   (β̃ = h² β),
//   Δλ = (−C − α̃ λ − γ ∇C·(x − xⁿ)) / ((1 + γ) ∇C W ∇Cᵀ + α̃),   Δx = W ∇Cᵀ Δλ.
// Converged, C + α̃ λ + γ ∇C·(x − xⁿ) = 0, i.e. λ = −h² (k_s C + k_d Ċ) with
// Ċ ≈ ∇C·(x − xⁿ)/h: a backward-Euler step of the damped spring force. α = 0
// is a hard constraint (γ = 0, no damping), projected as in plain PBD.
namespace particles {

struct Compliance {
  double alphaTilde = 0.0;  // α/h², force⁻¹·length·s⁻² scaled to the substep
  double gamma = 0.0;       // α β / h, dimensionless
};

// The compliance of a damped spring (k_s > 0, force/length; k_d ≥ 0, force/speed)
// over a substep h: α = 1/k_s, β = k_d.
inline Compliance springCompliance(double stiffness, double damping, double h) {
  return {1.0 / (stiffness * h * h), damping / (stiffness * h)};
}

// 1/((1 + γ) ∇C W ∇Cᵀ + α̃), the factor of Δλ; 0 when nothing can move
// (gradientWeight = ∇C W ∇Cᵀ = 0 and α̃ = 0).
inline double inverseDenominator(double gradientWeight, const Compliance& c) {
  const double denominator = (1.0 + c.gamma) * gradientWeight + c.alphaTilde;
  return denominator > 0.0 ? 1.0 / denominator : 0.0;
}

// Δλ from C, ∇C·(x − xⁿ) (displacement), λ and the inverse denominator above.
inline double multiplierStep(double C, double displacement, const Compliance& c, double lambda,
                             double inverseDenominator) {
  return (-C - c.alphaTilde * lambda - c.gamma * displacement) * inverseDenominator;
}

}  // namespace particles

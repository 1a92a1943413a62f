#pragma once
#include <memory>

#include "particles/integrator.h"

namespace particles {

// RATTLE (Andersen 1983; Leimkuhler & Reich, "Simulating Hamiltonian
// Dynamics", §7.2): velocity Verlet on the constraint manifold C(q) = 0, with
// the constraint forces as multipliers of the holonomic constraints themselves
// rather than of their second derivative. With W the inverse masses, Q the
// applied forces and J = ∂C/∂q:
//   v½ = v + (h/2) W (Q(x, v) + J(x)ᵀ λ)
//   x⁺ = x + h v½                      with λ such that C(x⁺) = 0   (SHAKE)
//   v⁺ = v½ + (h/2) W (Q(x⁺, v½) + J(x⁺)ᵀ μ)  with μ such that J(x⁺) v⁺ = 0
// Each projection moves along W Jᵀ, the direction of the constraint force.
// For forces of x alone the map is symplectic and time-reversible on the
// manifold, of order 2: the energy error stays bounded over long runs and the
// constraints hold to the projection tolerance at every step, with no
// Baumgarte feedback (k_s, k_d are not used). The acceleration-level schemes
// (symplectic Euler, Verlet) instead integrate J q̈ = −J̇ q̇ and let the
// feedback pull the drift back, which lets energy drift at O(h) or O(h²).
// Velocity-dependent forces (drag, damped springs) are evaluated at v½ in the
// second kick: the scheme stays second order but is then not symplectic.
//
// The position stage solves C(x̃ + W J(x)ᵀ Λ) = 0 for Λ by quasi-Newton
// iterations with the fixed matrix J(x) W J(x)ᵀ (its error contracts by
// O(h |v| / L) per pass); the velocity stage is one linear solve with
// J(x⁺) W J(x⁺)ᵀ. Both are solved by Jacobi-preconditioned conjugate gradient
// over the matrix-free operator to relative residual 1e-12; rows whose
// particles are all pinned are skipped. A step whose constraints are still
// violated by more than positionTolerance (relative to each constraint's
// length scale) when the passes end (maxPositionPasses, or a pass that shrinks
// the violation by less than 10%: a set that lost rank) is accepted up to
// failureTolerance and otherwise reports StepFailure::SolveFailed.
class RattleIntegrator : public Integrator {
 public:
  RattleIntegrator();
  ~RattleIntegrator() override;
  const char* name() const override { return "rattle"; }
  StepStats step(ParticleSystem& system, double dt) override;

  static constexpr double positionTolerance = 1e-11;  // max violation / length scale
  static constexpr double failureTolerance = 1e-6;
  static constexpr int maxPositionPasses = 50;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace particles

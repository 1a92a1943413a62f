#pragma once
// The user's hand: how stiff the mouse joint (forces/mouse_spring.h) is made
// when it grabs a particle, so that a grab feels alike in every scene.
//
// Box2D's mouse joint takes a frequency f and a damping ratio ζ and the mass
// m of the body it grabs, k = m ω², c = 2 m ζ ω (ω = 2πf), so every body
// follows the cursor alike. A particle is rarely a body of its own: springs
// and constraints tie it to others that it must drag along, and its springs
// hold it back where it is pulled. So a grab of particle p measures
//   M  the tied mass: p's own and that of every movable particle joined to it,
//      directly or through others, by a force that couples positions (a
//      nonzero block of ∂f/∂x: springs, angle springs) or by a constraint;
//   K  p's attached stiffness: the largest eigenvalue of p's own block of
//      −∂f/∂x over the scene's forces, the stiffness of its springs with their
//      far ends held (the definite Jacobians, Force::addDefiniteJacobians),
// and sets
//   k = max(M ω², ρ K),   c = 2 ζ √(k M).
// The first term makes the body of mass M follow as Box2D's body on an f Hz
// joint; the second keeps the steady gap small whatever holds p: a structure
// seen from p is never stiffer than p's own springs with their far ends held
// (K, the Schur complement's bound), so once settled p follows a move of the
// cursor to within K/(K + k) ≤ 1/(1 + ρ) of it: 10% at the default ρ = 9.
// Gravity shifts the particle by a constant M g/k that a move leaves alone.
//
// An integrator that applies the joint as an explicit force over a step h
// (explicitForceStep below; 0 for implicit Euler and xpbd, which take it
// implicitly) bounds both on p's own mass m:
//   √(k/m) h ≤ 1 (kExplicitJointRate = 0.4 where a constraint holds p),
//   c h/m ≤ 1/2
// (measured: velocity Verlet on the cloth diverges at c h/m = 1 and holds at
// 1/2; the linear limit √(k/m) h ≤ 1 is not enough where p turns rods, whose
// error grows with the square of the angle a rod turns in a step, and the
// cloth's springs need the whole of it to keep the 10% gap: the seed
// test chain (rods of 0.1 m, dt 0.01) dragged 0.28 m at its tip diverges
// under midpoint, RK4 and symplectic Euler at √(k/m) h = 1 and 0.52 and holds
// at 0.42 and below, the demo's DemoCompare.MouseDragReachesEveryPane).
#include <string>

#include "particles/forces/mouse_spring.h"

namespace particles {

class ParticleSystem;

// The largest √(k/m) h of a joint applied explicitly over a step h to a
// particle that a constraint holds (1 for one that none holds).
inline constexpr double kExplicitJointRate = 0.4;

struct MouseJointSettings {
  double frequency = 5.0;       // f, Hz: how briskly the grabbed body follows
  double dampingRatio = 0.7;    // ζ, non-dimensional: 1 is critical
  double stiffnessRatio = 9.0;  // ρ ≥ 0: k is at least ρ K (the follow gap at most 1/(1 + ρ))
  void validate() const;        // throws std::invalid_argument naming the field
};

// What a grab of one particle pulls.
struct GrabReach {
  double mass = 0.0;       // m, the particle's own
  double tiedMass = 0.0;   // M ≥ m
  double stiffness = 0.0;  // K, force / length
  bool constrained = false;  // a constraint holds the particle
};

// M and K of particle p at the system's present state; the force `ignore`
// (the joint being replaced) is left out.
GrabReach grabReach(const ParticleSystem& system, int particle, const Force* ignore = nullptr);

// The step h over which the integrator named `scheme` applies the joint as an
// explicit force: dt, or 0 for a scheme of the table that takes forces
// implicitly (IntegratorInfo::implicitForces).
double explicitForceStep(const std::string& scheme, double dt);

struct MouseSpringGains {
  double stiffness;  // k, force / length
  double damping;    // c, force / speed
};

// k and c by the rule above; explicitStep > 0 bounds them, 0 leaves them
// unbounded. Throws std::invalid_argument naming the value when the masses,
// the frequency or the ratios are out of range, or when k or c overflows (a
// mass near 1e306).
MouseSpringGains mouseSpringGains(const GrabReach& reach, const MouseJointSettings& joint, double explicitStep);

}  // namespace particles

#pragma once
// How the contact pass's coupled solve (src/collision/coupled_contacts.h) corrects the
// constraints' position drift, as each integrator asks (Integrator::driftCorrection).

namespace particles {

// How the coupled solve corrects the constraints' position drift.
enum class DriftCorrection {
  // Along the constraint gradients where the particles are; velocities untouched.
  AtEnd,
  // Along the gradients at the step's start (SHAKE's direction), each
  // correction Δx carried into the velocity as Δx/dt: for a scheme whose
  // step ends with x = x0 + dt v (symplectic Euler). A chain whipping at ω
  // under such a scheme, corrected at the end instead, gains a factor
  // 1 + (ω dt)² of its kinetic energy a step (its acceleration-level
  // constraint force moves it inward by dt² ω² r, twice the arc's sagitta,
  // and the correction outward turns that into speed along the arc).
  Shake,
};

}  // namespace particles

#pragma once
// Contacts, resolved after each whole step (never inside integrator stages):
// continuous against colliders, disc against disc, and collision edges
// (segments between particles, e.g. a cloth's springs) against colliders.
//
// Every contact sees the motion of a particle over the step as the path of
// constant acceleration through the step's two ends, finds the time τ the
// contact begins on that path, and applies a velocity change there; a
// velocity change Δv at τ moves the step's end by Δv·(dt − τ), so no position
// is corrected by hand and an elastic bounce in uniform gravity is exact. A
// contact that would close again within the step is resting: it holds the
// particle on the surface for the rest of the step with the normal impulse
// that cancels its approach (weight × dt for a particle at rest).
//
// The contact pass itself (its phases, broad phase and solves) is internal:
// src/collision/contact_pass.h.

namespace particles {

struct ContactSettings {
  int iterations = 100;   // Gauss–Seidel passes over resting contacts (stacks), after the first; ≥ 1
  // Work cap: impacts (and resting push-outs) one particle may take in one
  // step. Every impact in the step is resolved — a particle in a 1° wedge
  // meets its faces up to 180 times on one pass into the corner — and a
  // particle that would need more ends the step with
  // StepFailure::ContactCapReached (left at its last event, outside every
  // collider) rather than losing the motion silently; ≥ 1.
  int maxImpacts = 100000;
  double slop = 1e-9;     // world units: a gap this small counts as touching
  // The coupled solve of contacts and constraints (src/collision/coupled_contacts.h):
  int coupledIterations = 200;        // projected Gauss–Seidel sweeps over the shared rows, ≥ 1
  double coupledTolerance = 1e-10;    // m/s: stop when no row changes its velocity by more
  int positionIterations = 50;        // drift-correction passes over the same rows, ≥ 1
  double restitutionThreshold = 0.05; // m/s: a bounce slower than this rests instead
  // Disc against disc (collidable particles, ParticleSystem::setCollidable):
  double particleRestitution = 0.5;   // e in [0, 1]

  void validate() const;  // throws naming the bad field
};

// The box around the straight paths of particles over an interval, from x0
// to x, and their largest radius: when it meets no collider (and there are
// no discs or edges) no contact can begin, and the contact pass does nothing.
// of() gives it for particles [begin, end) of flat arrays (x0, y0, x1, …);
// merge() takes minima and maxima, so the box is the same however the
// particles were split. A coordinate that is not finite makes it unbounded.
struct PathBounds {
  double lo[2] = {kUnbounded, kUnbounded}, hi[2] = {-kUnbounded, -kUnbounded};
  double radius = 0.0;
  bool finite = true;

  static PathBounds of(const double* x0, const double* x, const double* radius, int begin, int end);
  void merge(const PathBounds& other);
  static constexpr double kUnbounded = 1.0e308;
};

// A collision edge: the segment between two particles (a spring of a cloth),
// which collider corners and discs cannot cross.
struct CollisionEdge {
  int a, b;  // particle indices
};

}  // namespace particles

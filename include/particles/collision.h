#pragma once
// Contacts, resolved after each whole step (never inside integrator stages;
// after each substep under xpbd) by one pipeline for every kind of contact:
// particles (points and discs) against colliders, discs against discs, and
// collision edges (segments between particles, e.g. a cloth's springs)
// against the corners of colliders. Its stages (src/collision/contact_pass.h):
// a broad phase, bounces at their exact times (impacts), a narrow phase per
// kind, and one solver for every contact together with the constraints that
// hold the particles it touches, friction inside it; then islands at rest
// may sleep (src/collision/islands.h).
//
// Every contact sees the motion of a particle over the step as the path of
// constant acceleration through the step's two ends (the impacts stage finds
// the time τ a bounce begins on that path and applies a velocity change
// there: a velocity change Δv at τ moves the step's end by Δv·(dt − τ), so an
// elastic bounce in uniform gravity is exact). A contact that does not bounce
// rests: the solver holds it on the surface, and within its friction cone
// where it began the step.

namespace particles {

struct ContactSettings {
  // Work cap: impacts (and resting push-outs) one particle may take in one
  // step. Every impact in the step is resolved — a particle in a 1° wedge
  // meets its faces up to 180 times on one pass into the corner — and a
  // particle that would need more ends the step with
  // StepFailure::ContactCapReached (left at its last event, outside every
  // collider) rather than losing the motion silently; ≥ 1.
  int maxImpacts = 100000;
  double slop = 1e-9;     // world units: a gap this small counts as touching
  // The contact solve (src/collision/contact_solver.h):
  int coupledIterations = 200;        // projected Gauss–Seidel sweeps over the velocities, ≥ 1
  double coupledTolerance = 1e-10;    // m/s: stop when no row changes its velocity by more
  int positionIterations = 50;        // nonlinear Gauss–Seidel passes over the positions, ≥ 1
  double restitutionThreshold = 0.05; // m/s: a bounce slower than this rests instead
  // Disc against disc (collidable particles, ParticleSystem::setCollidable):
  double particleRestitution = 0.5;   // e in [0, 1]
  double particleFriction = 0.0;      // Coulomb μ ≥ 0 between discs
  // Islands and sleep (src/collision/islands.h): an island whose particles
  // all move slower than sleepSpeed for sleepTime sleeps until something
  // touches it; sleepTime 0 turns sleep off.
  double sleepSpeed = 0.01;           // m/s, ≥ 0
  double sleepTime = 0.5;             // s, ≥ 0

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

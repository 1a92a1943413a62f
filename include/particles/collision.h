#pragma once
// Contacts, resolved after each whole step (never inside integrator stages):
// continuous against colliders, disc against disc, and collision edges
// (segments between particles, e.g. a cloth's springs) against colliders.
//
// Every contact sees the motion of a particle over the step as the path of
// constant acceleration through the step's two ends (contact_path.h), finds
// the time τ the contact begins on that path, and applies a velocity change
// there; a velocity change Δv at τ moves the step's end by Δv·(dt − τ), so no
// position is corrected by hand and an elastic bounce in uniform gravity is
// exact. A contact that would close again within the step is resting: it
// holds the particle on the surface for the rest of the step with the normal
// impulse that cancels its approach (weight × dt for a particle at rest).
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "particles/collider.h"

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
  // The coupled solve of contacts and constraints (coupled_contacts.h):
  int coupledIterations = 200;        // projected Gauss–Seidel sweeps over the shared rows, ≥ 1
  double coupledTolerance = 1e-10;    // m/s: stop when no row changes its velocity by more
  int positionIterations = 50;        // drift-correction passes over the same rows, ≥ 1
  double restitutionThreshold = 0.05; // m/s: a bounce slower than this rests instead

  void validate() const;  // throws naming the bad field
};

// What one contact pass did: the contacts it resolved and the particles that
// ran out of the work cap ContactSettings::maxImpacts (nonzero fails the step).
struct ContactCount {
  int contacts = 0;
  int capped = 0;
  ContactCount& operator+=(const ContactCount& other) {
    contacts += other.contacts;
    capped += other.capped;
    return *this;
  }
};

// The state at the start of the step, from which continuous detection sweeps.
// Each particle's path through the step runs from (x, v) here to its state as
// the integrator left it (contact_path.h); every contact pass reads it before
// any contact has changed that particle.
struct StepStart {
  const Eigen::VectorXd& x;  // 2n positions
  const Eigen::VectorXd& v;  // 2n velocities
  double dt;
};

// Particles (discs of radius[i], 0 for a point) against colliders: each
// particle's path over the step is swept against every collider; at the
// first impact the normal velocity becomes −e times the impact velocity and
// the tangential impulse is Coulomb's (at most μ times the normal impulse);
// the rest of the path is swept again from there, so touching colliders act
// as one closed boundary. Pinned particles (inverse mass 0) are never moved.
// `only` (null: all) lists the particles to resolve, the others are left
// alone. `lastFree` (2n) receives each resolved particle's end position (known
// to be outside every collider), from which pushOutOfColliders sweeps later.
// Returns the contacts and the particles that ran out of maxImpacts.
ContactCount resolveColliderContacts(const std::vector<Collider>& colliders, const StepStart& start,
                            const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                            const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v,
                            Eigen::VectorXd& lastFree, const std::vector<int>* only = nullptr);

// Broad phase against colliders, once a step: near[i] is set when particle
// i's path over the step (the box of x0 → x1) grown by `margin` meets a
// collider's bounding box or comes within margin of a half-plane. A particle
// not marked meets no collider if margin ≥ its radius (+ slop), and no edge
// with both ends unmarked meets a corner if margin ≥ edgeReach(). Linear in
// the number of particles, times the number of colliders; blocks of
// consecutive particles whose common box is apart from every collider are
// passed over with one test. nearList receives the marked particles, ascending.
void markNearColliders(const std::vector<Collider>& colliders, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1,
                       double margin, std::vector<char>& near, std::vector<int>& nearList);

// A resting pass for particles that another contact pushed into a collider
// after resolveColliderContacts: the path lastFree → x finds the face entered,
// the particle is put back on it and its approach (with Coulomb friction)
// removed. Updates lastFree; returns the contacts and the particles still
// entering a collider after maxImpacts passes.
ContactCount pushOutOfColliders(const std::vector<Collider>& colliders, const Eigen::VectorXd& inverseMass,
                       const Eigen::VectorXd& radius, const ContactSettings& settings, Eigen::VectorXd& x,
                       Eigen::VectorXd& v, Eigen::VectorXd& lastFree);

// Disc–disc contact between collidable particles, with a uniform-grid broad
// phase so the cost stays linear in the number of particles. With impacts,
// the discs' impacts on each other and on the colliders are taken in the
// order of their times within the step (each on the paths the discs follow
// then): a pair that meets exchanges the impulse j = −(1 + e) u_n / (w_i + w_j)
// at the time of impact (u_n the approach speed along the line of centres
// then), a collider impact is resolveColliderContacts'. A pair touching or
// overlapping at the step's end is resting: its approach is removed and its
// overlap split in proportion to inverse mass, which keeps momentum and the
// centre of mass.
class ParticleContacts {
 public:
  double restitution = 0.5;  // e in [0, 1]

  ParticleContacts();
  ~ParticleContacts();
  ParticleContacts(ParticleContacts&&) noexcept;
  ParticleContacts& operator=(ParticleContacts&&) noexcept;

  // impacts: the continuous pass of a step, from `start` (the colliders may be
  // empty); without, only the resting contacts at the step's end. lastFree
  // (may be null) receives the discs' end positions after their impacts, as
  // resolveColliderContacts' does. Returns the number of contacts resolved and
  // the discs that ran out of maxImpacts.
  // The pairs found touching are kept; resolveResting goes over them again
  // (alternating the order, which carries a push through a stack in both
  // directions) without a new broad phase, and returns the largest speed
  // change it made.
  ContactCount resolve(const std::vector<int>& collidable, const std::vector<Collider>& colliders,
                       const StepStart& start, const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                       const ContactSettings& settings, bool impacts, Eigen::VectorXd& x, Eigen::VectorXd& v,
                       Eigen::VectorXd* lastFree = nullptr);
  double resolveResting(const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                        const ContactSettings& settings, bool reverse, Eigen::VectorXd& x, Eigen::VectorXd& v);
  int touchingPairs() const { return static_cast<int>(touching_.size()); }

 private:
  // Pairs of collidable discs near enough to meet this step, as indices into `collidable`.
  void findCandidatePairs(const std::vector<int>& collidable, const Eigen::VectorXd& x, double cell);
  ContactCount resolveImpacts(const std::vector<int>& collidable, const std::vector<Collider>& colliders,
                              const StepStart& start, const Eigen::VectorXd& inverseMass,
                              const Eigen::VectorXd& radius, const ContactSettings& settings, Eigen::VectorXd& x,
                              Eigen::VectorXd& v, Eigen::VectorXd* lastFree);

  std::vector<std::pair<int, int>> touching_;  // pairs found in contact by the last resolve
  struct Scratch;  // broad phase and event queue, kept between steps to avoid allocation
  std::unique_ptr<Scratch> scratch_;
};

// A collision edge: the segment between two particles (a spring of a cloth),
// which collider corners and discs cannot cross.
struct CollisionEdge {
  int a, b;  // particle indices
};

// Edges against the corners of colliders (the vertices of boxes, polygons and
// capsules, and the centres of discs, grown by the collider's radius): a
// corner on one side of an edge at the step's start may not be on the other
// side, or nearer than its radius, at the end. The edge is pushed clear with
// the weights of the point of the edge facing the corner, its approach
// removed and Coulomb friction applied. A capsule's core may also not cross
// the edge over one of its ends (an end gone round a cap to the far side):
// that end is taken back along its step to where the edge passes the core on
// its starting side, outside every collider (by the particle's radius), and
// lastFree records it there. Returns the contacts.
// `candidates` (null: every edge is tested) lists the indices into `edges` to
// test, ascending: those with an end marked by markNearColliders (EdgeIncidence).
int resolveEdgeContacts(const std::vector<Collider>& colliders, const std::vector<CollisionEdge>& edges,
                        const StepStart& start, const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                        Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd& lastFree,
                        const std::vector<int>* candidates = nullptr);

// The last guard against an edge cutting through the core of a capsule or a
// disc: each candidate edge (indices into `edges`) that crosses a capsule's
// core at x but not at the step's start, or whose interior passed over a
// disc's centre (its ends moved in straight lines from the start to x), is
// taken back along the step of its ends to where it has not (passes until
// none is held, at most 16); returns how many times an edge was held.
int holdEdgesOffCores(const std::vector<Collider>& colliders, const std::vector<CollisionEdge>& edges,
                      const StepStart& start, const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                      Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd& lastFree,
                      const std::vector<int>& candidates);

// The collision edges at each particle, so that the edges with an end among
// a few marked particles are found without a pass over every edge.
class EdgeIncidence {
 public:
  // Rebuilds the table when `structure` differs from the last call's: a
  // ParticleSystem passes its structureStamp(), which changes with its
  // particles and its collision edges.
  void update(const std::vector<CollisionEdge>& edges, int particles, std::uint64_t structure);
  // Marks the edges with an end in `particles`.
  void mark(const std::vector<int>& particles);
  // The marked edges, as ascending indices into the edges; clears the marks.
  void takeMarked(std::vector<int>& out);

 private:
  std::optional<std::uint64_t> structure_;  // of the table as built
  std::vector<int> first_;     // particle p's edges: ids_[first_[p] .. first_[p + 1])
  std::vector<int> ids_;
  std::vector<char> marked_;   // per edge
};

// The largest side of an edge's box over the step (its two ends at x0 and
// x1): the margin markNearColliders needs for edges.
double edgeReach(const std::vector<CollisionEdge>& edges, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1);

}  // namespace particles

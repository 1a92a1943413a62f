#pragma once
// The collision phase of a step: one pipeline for every contact, as one
// object that owns its scratch.
//
// A pass over an interval dt that began at (x0, v0) and ends at the state the
// integrator left runs these stages in order:
// 1. broad phase (broad_phase.h): the particles whose paths come near a
//    collider, the collision edges at them, the pairs of discs near each other;
// 2. impacts (impacts.h): particles that move alone (in no constraint) bounce
//    at their exact times off colliders and each other;
// 3. narrow phase (narrow_phase.h): every contact at the step's end —
//    particle (point or disc) and collider, disc and disc, edge and corner;
// 4. solve (contact_solver.h): every contact and the constraints that hold
//    its particles as one system, positions then velocities, friction inside;
// 5. guards (boundary_guard.h): nothing left inside a collider or across a core.
// A particle that ran out of the impact work cap fails the step
// (StepFailure::ContactCapReached) rather than losing its motion silently.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "broad_phase.h"
#include "contact.h"
#include "contact_solver.h"
#include "contact_types.h"
#include "impacts.h"
#include "particles/collider.h"
#include "particles/collision.h"
#include "particles/constraint.h"
#include "particles/step_stats.h"

namespace particles {

// What a contact pass reads of a particle system, borrowed for one call.
struct ContactScene {
  const std::vector<Collider>& colliders;
  const std::vector<CollisionEdge>& edges;
  const std::vector<int>& discs;  // collidable particles (radius > 0)
  const ConstraintList& constraints;
  const Eigen::VectorXd& mass;
  const Eigen::VectorXd& inverseMass;
  const Eigen::VectorXd& radius;
  std::uint64_t structure;  // ParticleSystem::structureStamp()

  // Colliders or at least two discs: there is something to collide.
  bool colliding() const { return !colliders.empty() || discs.size() > 1; }
};

// Whether the constraints that hold the contacts' particles are rows of the
// solve (after every integrator's step; not in xpbd's substeps, whose
// constraint passes hold them).
struct ContactCoupling {
  bool withConstraints = false;
};

class ContactPass {
 public:
  ContactSettings& settings() { return settings_; }
  const ContactSettings& settings() const { return settings_; }

  // Starts a step at (x, v): checks the settings when the scene collides
  // (std::invalid_argument naming the bad field, before anything moves),
  // keeps the start state when `keepStart`, and clears the step's statistics.
  void beginStep(const ContactScene& scene, const Eigen::VectorXd& x, const Eigen::VectorXd& v, bool keepStart);
  // The pass over the whole step from the start kept by beginStep.
  int collideStep(const ContactScene& scene, double dt, const ContactCoupling& coupling, Eigen::VectorXd& x,
                  Eigen::VectorXd& v);
  // The pass over an interval dt from (x0, v0) to (x, v) (stages 1–5 above).
  // Returns the contacts resolved.
  int collide(const ContactScene& scene, const StepStart& start, const ContactCoupling& coupling, Eigen::VectorXd& x,
              Eigen::VectorXd& v);

  // Since beginStep: the solve's sweeps and residual and the step's failure
  // (internalSteps 0), and the contacts resolved.
  const StepStats& stepStats() const { return stats_; }
  int contactsThisStep() const { return contacts_; }
  // The contacts of the last pass (for islands).
  const std::vector<Contact>& lastContacts() const { return found_; }

  // Forgets the solve's multipliers (the state was replaced).
  void resetWarmStart() { solver_.resetWarmStart(); }

 private:
  void broadPhase(const ContactScene& scene, const StepStart& start, const Eigen::VectorXd& x);
  void sortMovers(const ContactScene& scene, const Eigen::VectorXd& x, const Eigen::VectorXd& v);
  ContactCount guard(const ContactScene& scene, const StepStart& start, Eigen::VectorXd& x, Eigen::VectorXd& v);

  ContactSettings settings_;
  Eigen::VectorXd startX_, startV_;  // the step's start (beginStep)
  // Broad phase.
  std::vector<char> near_;       // near a collider (markNearColliders)
  std::vector<int> nearList_;    // the same particles, ascending
  std::vector<int> nearEdges_;   // edges with an end near a collider or at a disc, ascending
  EdgeIncidence edgeIncidence_;
  DiscGrid grid_;
  std::vector<std::pair<int, int>> discPairs_;  // indices into the scene's discs
  bool pairsCapped_ = false;                    // the broad phase found more pairs than a step takes on
  // Impacts: the particles that move alone.
  enum class Alone : std::uint8_t { Free, Anchored, Held };  // no constraint; only to pinned particles; else
  std::uint64_t moversStructure_ = 0;
  std::vector<Alone> alone_;
  std::vector<std::vector<int>> constraintsOf_;  // an anchored particle's constraints
  std::vector<Anchored> anchored_;               // this step's anchored movers, by particle
  std::vector<int> points_, moverDiscs_, moverIndex_;
  std::vector<std::pair<int, int>> moverPairs_;  // indices into moverDiscs_
  References refs_;
  Impacts impacts_;
  // Narrow phase and solve.
  std::vector<Contact> found_;
  Eigen::VectorXd lastFree_, freeX_, freeV_;  // the guards' last free positions; the state before the solve
  ContactSolver solver_;
  StepStats stats_;
  int contacts_ = 0;
};

}  // namespace particles

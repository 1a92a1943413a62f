#pragma once
// The collision phase of a step, as one object that owns its scratch.
//
// A pass over an interval dt that began at (x0, v0) and ends at the state the
// integrator left runs these phases in order:
// 1. discs: collidable discs meet each other and the colliders in the order
//    of their impacts (ParticleContacts::resolve);
// 2. near: every other particle whose path comes near a collider is marked
//    (and every collision edge with an end near one);
// 3. walls: the marked particles meet the colliders, each on its own, except
//    the constrained particles touching a collider and every particle joined
//    to them by constraints, which are resolved with those constraints when
//    the step's integrator asks for it (coupled_contacts.h);
// 4. edges: collision edges swept against the colliders' corners and cores;
// 5. resting: Gauss–Seidel passes over discs, edges and colliders until
//    nothing is pushed (colliders last, as the hard boundary).
// A particle that ran out of the impact work cap fails the step
// (StepFailure::ContactCapReached) rather than losing its motion silently.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "collider_broad_phase.h"
#include "contact_types.h"
#include "coupled_contacts.h"
#include "particle_contacts.h"
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

// Whether constrained particles that touch a collider are resolved with their
// constraints (after every integrator's step; not in xpbd's substeps, whose
// constraint passes hold them), and how that solve corrects the constraints'
// drift (Integrator::driftCorrection).
struct ContactCoupling {
  bool withConstraints = false;
  DriftCorrection drift = DriftCorrection::AtEnd;
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
  // The pass over an interval dt from (x0, v0) to (x, v) (phases 1–5 above).
  // Returns the contacts resolved.
  int collide(const ContactScene& scene, const StepStart& start, const ContactCoupling& coupling, Eigen::VectorXd& x,
              Eigen::VectorXd& v);

  // Since beginStep: the coupled solve's sweeps and residual and the step's
  // failure (internalSteps 0), and the contacts resolved.
  const StepStats& stepStats() const { return stats_; }
  int contactsThisStep() const { return contacts_; }

  // Forgets the coupled solve's impulses (the state was replaced).
  void resetWarmStart() { coupled_.resetWarmStart(); }

 private:
  ContactCount collideWalls(const ContactScene& scene, const StepStart& start, const ContactCoupling& coupling,
                            Eigen::VectorXd& x, Eigen::VectorXd& v);
  ContactCount restingPasses(const ContactScene& scene, const StepStart& start, bool edgesCaught,
                             Eigen::VectorXd& x, Eigen::VectorXd& v);

  ParticleContacts discs_;
  ContactSettings settings_;
  Eigen::VectorXd startX_, startV_;  // the step's start (beginStep)
  Eigen::VectorXd lastFree_;         // each particle's last position known outside every collider
  std::vector<char> near_;           // near a collider (markNearColliders) and not a disc
  std::vector<int> nearList_;        // the same particles, ascending
  std::vector<int> nearEdges_;       // edges with an end near a collider or at a disc, ascending
  EdgeIncidence edgeIncidence_;
  CoupledContacts coupled_;
  std::vector<int> touching_, singles_;
  StepStats stats_;
  int contacts_ = 0;
};

}  // namespace particles

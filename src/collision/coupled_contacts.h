#pragma once
// Contacts and constraints solved as one system, after an explicit step.
//
// A particle held by a rod, wire or line that touches a collider cannot be
// resolved on its own: the bounce or the resting impulse given to it breaks
// the constraint, and the integrator's next acceleration-level solve turns the
// broken constraint into a large force (a chain landing on a floor explodes).
// So the particles that touch a collider and every particle joined to them by
// a chain of constraints (an island) are resolved together, as Box2D's soft
// step relaxes joints and contacts together:
//
// 1. Rows. Each constraint of the island gives a bilateral row, its J from
//    Constraint::evaluate at the step's end (target J v = 0, λ free). Each
//    collider a particle's path entered (or that it ends within slop of)
//    gives a unilateral normal row on the plane of the face entered (target
//    v_n ≥ v⁺, λ_n ≥ 0) and a friction row along the face (target v_t = 0,
//    |λ_t| ≤ μ λ_n): Coulomb's cone, boxed by the current λ_n.
// 2. Restitution. A contact new this step bounces: v⁺ = e |v_impact|, where
//    the impact speed is recovered from the end speed and the depth reached,
//    v_impact² = v_n² + 2 a_n d (a_n the normal acceleration over the step),
//    so the bounce never carries the speed gained inside the collider; below
//    restitutionThreshold, and for contacts that persist from the last step,
//    v⁺ = 0 (resting).
// 3. Positions: nonlinear Gauss–Seidel over the rows' position errors,
//    C = 0 for the constraints and n·(x − p) ≥ 0 for the contact planes,
//    each row moving its particles along W Jᵀ (velocities untouched), until
//    the largest error is below the slop or `positionIterations` passes.
//    (The constraints alone are corrected once before the contacts are
//    found, so integrator drift off a wire does not make a contact.) The
//    constraint rows are then evaluated again where the particles now are.
// 4. Velocities: projected Gauss–Seidel over all rows (constraints, then
//    friction, then normals, so the unilateral rows are the last word),
//    warm-started from the last step's impulses of the same constraint and
//    the same (particle, collider) contact, until no row changes its
//    velocity by more than `coupledTolerance` (m/s) or `coupledIterations`
//    sweeps; the sweeps and that last change go to StepStats
//    (contactIterations, contactResidual). Solving velocities last leaves
//    J v = 0 at the final positions.
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "contact_types.h"
#include "particles/collider.h"
#include "particles/collision.h"
#include "particles/constraint.h"
#include "particles/drift_correction.h"

namespace particles {

// Whether a particle of radius r moving a → b over the step enters a
// collider or ends within slop of one: it then has contact rows.
bool touchesCollider(const std::vector<Collider>& colliders, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     double r, double slop);

struct CoupledSolveStats {
  int rows = 0;           // rows of the last solve (constraints + normals + friction)
  int iterations = 0;     // velocity sweeps made
  double residual = 0.0;  // largest velocity change of a row in the last sweep, m/s
  int contacts = 0;       // contact (normal) rows
};

class CoupledContacts {
 public:
  CoupledContacts();
  ~CoupledContacts();
  CoupledContacts(CoupledContacts&&) noexcept;
  CoupledContacts& operator=(CoupledContacts&&) noexcept;

  // The islands of the particles in `touching` (ascending or not): those
  // particles and every particle reachable from them through constraints.
  // Returns the island's particles, ascending. Rebuilds its adjacency when
  // `structure` changes.
  const std::vector<int>& island(const ConstraintList& constraints, int particles, std::uint64_t structure,
                                 const std::vector<int>& touching);

  const std::vector<int>& lastIsland() const { return island_; }

  // Whether particle i belongs to a constraint.
  bool constrained(int i) const { return i < static_cast<int>(first_.size()) - 1 && first_[i + 1] > first_[i]; }

  // Resolves the island last returned by island() (steps 1–4 above), from
  // the step's start `start` to the state (x, v) the integrator left; the
  // constraints' drift corrected as `drift` says.
  CoupledSolveStats solve(const ConstraintList& constraints, const std::vector<Collider>& colliders,
                          const StepStart& start, const Eigen::VectorXd& mass, const Eigen::VectorXd& inverseMass,
                          const Eigen::VectorXd& radius, const ContactSettings& settings, DriftCorrection drift,
                          Eigen::VectorXd& x, Eigen::VectorXd& v);

  void resetWarmStart() { previous_.clear(); }

 private:
  void buildAdjacency(const ConstraintList& constraints, int particles);
  void collectIslandConstraints(const ConstraintList& constraints);
  int addContacts(const std::vector<Collider>& colliders, const StepStart& start, const Eigen::VectorXd& inverseMass,
                  const Eigen::VectorXd& radius, const ContactSettings& settings, const Eigen::VectorXd& x,
                  const Eigen::VectorXd& v);

  std::uint64_t structure_ = 0;
  std::vector<int> first_, ids_;  // particle p's constraints: ids_[first_[p] .. first_[p + 1])
  std::vector<char> inIsland_;
  std::vector<int> island_, queue_;
  // Last step's impulses: constraint rows keyed −1 − index, contact rows
  // keyed (particle, collider, normal or friction).
  std::unordered_map<std::int64_t, double> previous_;
  struct Rows;  // the solve's rows and their scratch, kept between steps to avoid allocation
  std::unique_ptr<Rows> rows_;
};

}  // namespace particles

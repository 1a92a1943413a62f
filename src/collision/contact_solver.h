#pragma once
// Every contact of a step and the constraints that hold its particles, solved
// as one system after the integrator's step (or after each of xpbd's
// substeps), in the stages of Box2D's soft step (its src/solver.c) with hard
// rows: one row per contact normal (impulse λ_n ≥ 0), one per friction
// direction (|λ_t| ≤ μ λ_n, Coulomb's cone, bounded by the normal's present
// impulse) and one per constraint on the particles the contacts touch and
// every particle joined to them by constraints (bilateral, λ free).
//
// 0. Start on the constraints: the references of the particles the
//    constraints hold are put back on them (Newton steps, as stage 3), so that
//    a contact is judged where the constraints hold its particle (a bead the
//    integrator let drift off its wire into a floor tangent to the wire does
//    not touch that floor).
// 1. Solve. The velocities at the step's end, from where the integrator left
//    them: J v = 0 for the constraints at the particles' references (the
//    step's start, or a particle's last bounce), v_n ≥ −g/h for each contact
//    (g its gap at the references, h the time left: it may close its gap over
//    the step and no more), and friction's v_t → 0 within the cone, all before
//    any position moves.
// 2. Integrate positions: every particle the rows hold moves from its
//    reference by h v, so a contact within its friction cone (v_t = 0) leaves
//    its particle where it was, under every integrator: no creep on a slope,
//    a rope over a capstan holds. (The particles the rows do not hold keep
//    the integrator's positions.)
// 3. Project. The constraints' drift of that move is corrected by Newton
//    steps along their gradients at the references (SHAKE's direction, carried
//    into the velocity as Δx/h), solved directly over each island's
//    constraints (a sparse LU: a chain of any length in one solve), in turn
//    with Gauss–Seidel passes that push the contacts the linearised solve
//    left overlapping (a disc on a curved surface) out along their normals,
//    until every error is within the slop.
// 4. Relax. The velocities again at the final positions (J v = 0, v_n ≥ v⁺,
//    friction), continuing from stage 1's impulses, so no push of stage 1 or
//    3 is left as speed; a new contact that struck bounces here with
//    v⁺ = e × its impact speed (Box2D applies restitution after the relax).
// Stages 1 and 4 are block Gauss–Seidel: in each sweep the island's
// constraints are solved directly (LDLᵀ of J W Jᵀ), then friction and normal
// rows relaxed one by one (projected Gauss–Seidel), so that the unilateral
// rows have the last word; they are warm-started from the last step's
// impulses of the same rows (contact keys, constraint indices), so a resting
// pile or rope, which needs the same impulses every step, is solved by its
// warm start. They stop when no row changes a velocity by more than
// ContactSettings::coupledTolerance or at coupledIterations; the sweeps and
// the last change go to StepStats.
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "contact.h"
#include "contact_types.h"
#include "particles/collision.h"
#include "particles/constraint.h"

namespace particles {

struct ContactSolveStats {
  int rows = 0;           // rows of the solve (constraints + normals + friction)
  int positionPasses = 0; // projection passes made
  int iterations = 0;     // velocity sweeps made
  double residual = 0.0;  // largest velocity change of a row in the last sweep, m/s
};

// What the solve reads besides the contacts.
struct ContactSolveInput {
  const ConstraintList& constraints;
  const Eigen::VectorXd& mass;
  const Eigen::VectorXd& inverseMass;
  References& refs;                  // each particle's reference: where its path over the time h left starts
  bool withConstraints;              // constraints as rows (not under xpbd, whose projections hold them)
};

class ContactSolver {
 public:
  ContactSolver();
  ~ContactSolver();
  ContactSolver(ContactSolver&&) noexcept;
  ContactSolver& operator=(ContactSolver&&) noexcept;

  // Solves the contacts and the constraints that hold their particles,
  // moving (x, v) from the step's end as the integrator and the impacts left
  // it (stages 1–4 above). structure: ParticleSystem::structureStamp().
  ContactSolveStats solve(std::vector<Contact>& contacts, const ContactSolveInput& in, std::uint64_t structure,
                          const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v);

  // Whether the contact with this key was in the last solve (it is not new).
  bool persists(std::uint64_t key) const;
  // The side (Contact::side) of the contact with this key in the last solve,
  // 0 when it was not in it.
  double lastSide(std::uint64_t key) const;

  // The particles the last solve moved (its contacts' and the constraints'
  // it included), ascending.
  const std::vector<int>& lastParticles() const { return island_; }

  void resetWarmStart();

 private:
  struct Rows;  // the rows, their scratch and the last step's multipliers
  static void solveIsland(Rows& rows, int island, const ContactSettings& settings, Eigen::VectorXd& v,
                          ContactSolveStats& stats);
  std::unique_ptr<Rows> rows_;
  std::vector<int> island_;
};

}  // namespace particles

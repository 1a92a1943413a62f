#pragma once
// State (q, q̇, force accumulator, inverse masses), the force and constraint
// objects acting on it, and the derivative evaluation that integrators drive.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "particles/collider.h"
#include "particles/collision.h"
#include "particles/constraint.h"
#include "particles/constraint_solver.h"
#include "particles/force.h"
#include "particles/integrator.h"

namespace particles {

// A copy of the dynamic state, for rewinding.
struct Snapshot {
  Eigen::VectorXd x, v;
  double time = 0.0;
};

class ContactPass;  // the collision phase of a step (src/collision/contact_pass.h)
struct ContactScene;
class Islands;      // islands and sleep (src/collision/islands.h)
struct TearSettings;       // particles/tearing.h
struct ThreadUseSettings;  // particles/threads.h

class ParticleSystem {
 public:
  ParticleSystem();
  ~ParticleSystem();
  ParticleSystem(ParticleSystem&&) noexcept;
  ParticleSystem& operator=(ParticleSystem&&) noexcept;

  // --- building -----------------------------------------------------------
  // Returns the new particle's index. mass must be finite and > 0.
  int addParticle(const Eigen::Vector2d& position, double mass,
                  const Eigen::Vector2d& velocity = Eigen::Vector2d::Zero());
  // Adds many particles at rest with one reallocation (large cloths); returns
  // the index of the first.
  int addParticles(const std::vector<Eigen::Vector2d>& positions, const std::vector<double>& masses);
  // Changes the mass (finite, > 0) of particle i; a pinned particle stays pinned.
  void setMass(int i, double mass);
  // A pinned particle has inverse mass 0 and never moves; pinning zeroes its velocity.
  void setPinned(int i, bool pinned);
  bool pinned(int i) const { return inverseMass_[i] == 0.0; }
  // Makes particle i a disc of the given radius (> 0) for particle–particle contact.
  void setCollidable(int i, double radius);
  bool collidable(int i) const { return radius_[i] > 0.0; }

  // Take ownership; throw std::invalid_argument if an index is out of range.
  Force& addForce(std::unique_ptr<Force> force);
  Constraint& addConstraint(std::unique_ptr<Constraint> constraint);
  // Validates the collider (std::invalid_argument naming the bad field).
  void addCollider(const Collider& collider);
  // Makes the segment between particles a and b collide with colliders (a cloth's springs).
  void addCollisionEdge(int a, int b);
  // Removes a force previously added (e.g. the mouse spring on release).
  void removeForce(const Force* force);
  // Tears (enabled = false) or mends a spring or angle spring added to this
  // system: a torn one adds no force, potential or Jacobian. Changes the
  // structure stamp (the spring batch is rebuilt at the next evaluation,
  // O(forces)). std::invalid_argument if it is neither of this system.
  void setSpringEnabled(const Force* spring, bool enabled);
  // Breaks the links between the given particle pairs (either order): every
  // force drops what hangs on them (Force::dropLinks: the springs on them
  // tear, angle springs with them as an arm go, the wind stops pushing on
  // them) and the collision edges on them are removed; the links that break
  // with them (Force::linksBreakingWith: a torn face's diagonals) break too.
  // Returns how many forces changed; changes the structure stamp. The tear
  // phase of step() calls it (tearing.h).
  int breakLinks(const std::vector<std::array<int, 2>>& links);
  // Every link broken so far, (min, max), in the order they broke.
  const std::vector<std::array<int, 2>>& brokenLinks() const { return brokenLinks_; }
  // Springs that break when stretched too far, decided once per step.
  TearSettings& tearing();
  const TearSettings& tearing() const;
  // Links broken by the tear phase of the last step.
  int tornLastStep() const;

  // --- state --------------------------------------------------------------
  int size() const { return static_cast<int>(mass_.size()); }
  // Read-only: only an integrator advances the state in place (Integrator's
  // protected access); everything else sets it through the setters below.
  const Eigen::VectorXd& positions() const { return x_; }
  const Eigen::VectorXd& velocities() const { return v_; }
  // Every particle's position or velocity (2n values; std::invalid_argument
  // for another size), or particle i's (requireIndex). The clock, forces and
  // constraints are left as they are; an adaptive scheme's carried solution
  // restarts from the new state (particles/step_continuation.h).
  void setPositions(const Eigen::VectorXd& x);
  void setVelocities(const Eigen::VectorXd& v);
  void setPosition(int i, const Eigen::Vector2d& p);
  void setVelocity(int i, const Eigen::Vector2d& v);
  Eigen::Vector2d position(int i) const { return x_.segment<2>(2 * i); }
  Eigen::Vector2d velocity(int i) const { return v_.segment<2>(2 * i); }
  const Eigen::VectorXd& masses() const { return mass_; }
  const Eigen::VectorXd& inverseMasses() const { return inverseMass_; }
  const Eigen::VectorXd& radii() const { return radius_; }
  // Force accumulator Q + Q̂ of the last evaluation (2n).
  const Eigen::VectorXd& forces() const { return f_; }
  double time() const { return time_; }
  Phase phase() const { return {x_, v_, mass_, inverseMass_}; }
  Phase phase(const Eigen::VectorXd& x, const Eigen::VectorXd& v) const {
    return {x, v, mass_, inverseMass_};
  }

  Snapshot snapshot() const { return {x_, v_, time_}; }
  void restore(const Snapshot& s);

  const std::vector<std::unique_ptr<Force>>& forceObjects() const { return forces_; }
  // Some force follows the clock (Force::timeDependent): it changes from one step to the next.
  bool hasTimeDependentForces() const { return !clocked_.empty(); }
  // Changes whenever particles, forces, constraints, pins or collision edges
  // change, and differs between systems: integrators and the contact pass
  // that prepare per-structure data key it on this.
  std::uint64_t structureStamp() const { return structureStamp_; }
  const ConstraintList& constraints() const { return constraints_; }
  const std::vector<Collider>& colliders() const { return colliders_; }
  const std::vector<CollisionEdge>& collisionEdges() const { return edges_; }

  ConstraintSolver& solver() { return solver_; }
  const ConstraintSolver& solver() const { return solver_; }
  // Contact settings, particleRestitution among them (checked at the next step).
  ContactSettings& contactSettings();
  const ContactSettings& contactSettings() const;

  // --- dynamics -----------------------------------------------------------
  // q̈ at (x, v): clear forces → apply forces → solve λ → add Jᵀλ → a = W(Q + Q̂).
  // The constraint solve is skipped when there are no constraints. Each call
  // is tallied (one force evaluation, the solve's statistics) for takeEvaluationStats().
  // (The explicit schemes fuse their stages into this pass: src/system_internals.h.)
  void acceleration(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& a);
  // The applied forces Q at (x, v) alone (every force object, no constraint
  // forces) into f: the first two phases of acceleration(), for schemes that
  // impose the constraints themselves (RATTLE). Tallied as one force evaluation.
  void appliedForces(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& f);

  // The force evaluations and constraint solves made through acceleration()
  // since the last call (or the start of the step), as the statistics of one
  // fixed step (internalSteps = 1); resets the tally. Integrators return it
  // from step(), adding their own counts.
  StepStats takeEvaluationStats();
  // The same tally added to stats, a step that counts its own internal steps
  // (stats.internalSteps unchanged); resets the tally.
  void addEvaluationStats(StepStats& stats);

  // One step, as named phases: begin (check the settings, choose the
  // threads, keep the start state, tell time-dependent forces the clock) →
  // integrate by dt → collide
  // (the contact pass, src/collision/contact_pass.h, continuous from the start
  // state; skipped without colliders or collidable discs, and left to the
  // integrator when it collides inside its substeps) → sleep (islands at rest
  // fall asleep and are held, src/collision/islands.h; with everything
  // asleep the step integrates and collides nothing) → tear (tearing.h;
  // skipped when off) → advance the clock. Throws std::invalid_argument for dt ≤ 0 or NaN.
  // Returns the integrator's statistics of the step, also kept as lastStepStats().
  // The step runs on threadUse()'s choice of threads, at most threadCount()
  // (particles/threads.h), reported as StepStats::threads.
  StepStats step(Integrator& integrator, double dt);
  const StepStats& lastStepStats() const { return lastStepStats_; }
  // How step() chooses its threads (particles/threads.h).
  ThreadUseSettings& threadUse();
  const ThreadUseSettings& threadUse() const;

  // Colliders or at least two collidable discs: step() has a collision phase.
  bool colliding() const;
  // The contact pass over an interval dt that began at (x0, v0) and ends at
  // the present state, each particle on its own. An
  // integrator that collides inside its substeps (Integrator::collidesInSubsteps)
  // runs it after each substep. Returns the contacts, which contactsLastStep() sums.
  // paths: the box of the paths from x0 to the present state (PathBounds),
  // when the caller measured it in a pass of its own; else the pass measures it.
  int collideOver(const Eigen::VectorXd& x0, const Eigen::VectorXd& v0, double dt,
                  const PathBounds* paths = nullptr);

  // --- diagnostics --------------------------------------------------------
  double kineticEnergy() const;
  double potentialEnergy() const;  // sum over forces that have a potential
  double totalEnergy() const { return kineticEnergy() + potentialEnergy(); }
  double maxConstraintError() const;          // max violation, world units
  double maxRelativeConstraintError() const;  // max violation / length scale
  // The last constraint solve alone; lastStepStats() sums a whole step.
  const SolveStats& lastSolve() const { return solver_.stats(); }
  bool finite() const;  // every position and velocity finite
  int contactsLastStep() const;
  // Particles asleep (islands at rest, src/collision/islands.h); any edit of
  // the system or its state wakes them all.
  int sleeping() const;

 private:
  friend class Integrator;       // advances x_ and v_ in place (Integrator::positionsOf)
  friend struct SystemInternals;  // the engine's own passes over the system (src/system_internals.h)
  // The force batches (forces_ as flat arrays, rebuilt on a structure
  // change), the tear phase and the thread-use controller (src/particle_system.cpp).
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Eigen::VectorXd x_, v_, f_;
  Eigen::VectorXd mass_, inverseMass_, radius_;
  double time_ = 0.0;
  std::vector<std::unique_ptr<Force>> forces_;
  std::vector<Force*> clocked_;  // the time-dependent ones among forces_, told the clock each step
  ConstraintList constraints_;
  std::vector<Collider> colliders_;
  std::vector<CollisionEdge> edges_;
  std::vector<std::array<int, 2>> brokenLinks_;
  std::vector<int> collidable_;
  ConstraintSolver solver_;
  std::unique_ptr<ContactPass> contacts_;
  std::unique_ptr<Islands> islands_;
  void wake();
  StepStats evaluations_;  // tally of acceleration(); its internalSteps is not used
  StepStats lastStepStats_;
  std::uint64_t structureStamp_ = nextStructureStamp();
  static std::uint64_t nextStructureStamp();
  ContactScene contactScene() const;
};

}  // namespace particles

#include "particles/particle_system.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>

#include "particles/check.h"
#include "particles/forces/spring.h"

namespace particles {

std::uint64_t ParticleSystem::nextStructureStamp() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

int ParticleSystem::addParticle(const Eigen::Vector2d& position, double mass,
                                const Eigen::Vector2d& velocity) {
  requireFinite("particle velocity.x", velocity.x());
  requireFinite("particle velocity.y", velocity.y());
  const int i = addParticles({position}, {mass});
  v_.segment<2>(2 * i) = velocity;
  return i;
}

int ParticleSystem::addParticles(const std::vector<Eigen::Vector2d>& positions,
                                 const std::vector<double>& masses) {
  if (positions.size() != masses.size())
    throw std::invalid_argument("addParticles needs one mass per position");
  for (std::size_t k = 0; k < positions.size(); ++k) {
    requireFinite("particle position.x", positions[k].x());
    requireFinite("particle position.y", positions[k].y());
    requirePositive("particle mass", masses[k]);
  }
  structureStamp_ = nextStructureStamp();
  const int first = size(), n = first + static_cast<int>(positions.size());
  x_.conservativeResize(2 * n);
  v_.conservativeResize(2 * n);
  f_.conservativeResize(2 * n);
  mass_.conservativeResize(n);
  inverseMass_.conservativeResize(n);
  radius_.conservativeResize(n);
  for (int i = first; i < n; ++i) {
    x_.segment<2>(2 * i) = positions[i - first];
    v_.segment<2>(2 * i).setZero();
    f_.segment<2>(2 * i).setZero();
    mass_[i] = masses[i - first];
    inverseMass_[i] = 1.0 / mass_[i];
    radius_[i] = 0.0;
  }
  return first;
}

void ParticleSystem::setMass(int i, double mass) {
  requireIndex("setMass", i, size());
  requirePositive("particle mass", mass);
  mass_[i] = mass;
  if (inverseMass_[i] != 0.0) inverseMass_[i] = 1.0 / mass;
  structureStamp_ = nextStructureStamp();
}

void ParticleSystem::setPinned(int i, bool pin) {
  requireIndex("setPinned", i, size());
  inverseMass_[i] = pin ? 0.0 : 1.0 / mass_[i];
  structureStamp_ = nextStructureStamp();
  if (pin) v_.segment<2>(2 * i).setZero();
}

void ParticleSystem::setCollidable(int i, double radius) {
  requireIndex("setCollidable", i, size());
  requirePositive("particle radius", radius);
  if (radius_[i] == 0.0) collidable_.push_back(i);
  radius_[i] = radius;
}

Force& ParticleSystem::addForce(std::unique_ptr<Force> force) {
  for (int i : force->particles()) requireIndex(force->type(), i, size());
  forces_.push_back(std::move(force));
  structureStamp_ = nextStructureStamp();
  return *forces_.back();
}

Constraint& ParticleSystem::addConstraint(std::unique_ptr<Constraint> constraint) {
  for (int i : constraint->particles()) requireIndex(constraint->type(), i, size());
  constraints_.push_back(std::move(constraint));
  structureStamp_ = nextStructureStamp();
  solver_.resetWarmStart();
  return *constraints_.back();
}

void ParticleSystem::addCollider(const Collider& collider) {
  collider.validate();
  colliders_.push_back(collider);
}

void ParticleSystem::addCollisionEdge(int a, int b) {
  requireIndex("collision edge", a, size());
  requireIndex("collision edge", b, size());
  if (a == b) throw std::invalid_argument("collision edge joins particle " + std::to_string(a) + " to itself");
  edges_.push_back({a, b});
  structureStamp_ = nextStructureStamp();
}

void ParticleSystem::removeForce(const Force* force) {
  forces_.erase(std::remove_if(forces_.begin(), forces_.end(),
                               [&](const std::unique_ptr<Force>& f) { return f.get() == force; }),
                forces_.end());
  structureStamp_ = nextStructureStamp();
}

void ParticleSystem::setSpringEnabled(const Force* spring, bool enabled) {
  const auto found = std::find_if(forces_.begin(), forces_.end(),
                             [&](const std::unique_ptr<Force>& f) { return f.get() == spring; });
  auto* asSpring = found == forces_.end() ? nullptr : dynamic_cast<SpringForce*>(found->get());
  if (!asSpring) throw std::invalid_argument("setSpringEnabled: not a spring of this system");
  if (asSpring->enabled_ == enabled) return;
  asSpring->enabled_ = enabled;
  structureStamp_ = nextStructureStamp();
}

void ParticleSystem::restore(const Snapshot& s) {
  if (s.x.size() != x_.size() || s.v.size() != v_.size())
    throw std::invalid_argument("snapshot was taken of a system of another size");
  x_ = s.x;
  v_ = s.v;
  time_ = s.time;
  solver_.resetWarmStart();
  coupled_.resetWarmStart();
}

void ParticleSystem::acceleration(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                  Eigen::VectorXd& a) {
  const Phase s = phase(x, v);
  batches_.update(forces_, structureStamp_);
  const bool fuseTail = constraints_.empty();  // nothing is added to f after the forces
  batches_.apply(s, f_, fuseTail);
  ++evaluations_.forceEvaluations;
  if (fuseTail) {
    batches_.applyTailAndDivide(s, f_, a);
    return;
  }
  {
    solver_.addConstraintForces(s, constraints_, f_);
    const SolveStats& solve = solver_.stats();
    StepStats one{};
    one.solves = 1;
    one.cgIterations = solve.iterations;
    one.maxResidual = solve.residual;
    one.factorizations = solve.factorizations;
    one.internalSteps = 0;
    if (solve.failed) one.failure = StepFailure::SolveFailed;
    evaluations_ += one;
  }
  a.resize(x.size());
  for (int i = 0; i < size(); ++i) a.segment<2>(2 * i) = inverseMass_[i] * f_.segment<2>(2 * i);
}

void ParticleSystem::appliedForces(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& f) {
  batches_.update(forces_, structureStamp_);
  batches_.apply(phase(x, v), f, false);
  ++evaluations_.forceEvaluations;
}

StepStats ParticleSystem::takeEvaluationStats() {
  StepStats taken = evaluations_;
  taken.internalSteps = 1;  // the tally counts evaluations, not steps
  evaluations_ = StepStats{};
  return taken;
}

void ParticleSystem::addEvaluationStats(StepStats& stats) {
  StepStats taken = takeEvaluationStats();
  taken.internalSteps = 0;
  stats += taken;
}

StepStats ParticleSystem::step(Integrator& integrator, double dt) {
  requirePositive("dt", dt);
  evaluations_ = StepStats{};
  // Settings are public fields: check them before anything moves, so a bad
  // value never leaves a step half done.
  solver_.settings.validate();
  const bool collideAfter = colliding() && !integrator.collidesInSubsteps();
  if (colliding()) {
    contactSettings_.validate();
    if (collidable_.size() > 1)
      requireInRange("particle contact restitution", contacts_.restitution, 0.0, 1.0);
  }
  if (collideAfter) {
    startX_ = x_;
    startV_ = v_;
  }
  contactsLastStep_ = 0;
  coupleContacts_ = collideAfter && integrator.couplesContactsWithConstraints();
  contactStats_ = StepStats{};
  contactStats_.internalSteps = 0;
  StepStats stats = integrator.step(*this, dt);
  addEvaluationStats(stats);  // evaluations the integrator left in the tally
  if (collideAfter) collideOver(startX_, startV_, dt);
  coupleContacts_ = false;
  stats += contactStats_;
  time_ += dt;
  lastStepStats_ = stats;
  return stats;
}

namespace {
// Every straight path a contact sweeps (particle or edge, from x0 to x) lies
// in the box around all of x0 and x grown by `grow`: when that box meets no
// collider's bounds (a half-plane has none), no sweep can hit, and a substep's
// collision pass over a cloth far from the walls costs one pass over the positions.
bool pathsMayReachColliders(const std::vector<Collider>& colliders, const Eigen::VectorXd& x0,
                            const Eigen::VectorXd& x, double grow) {
  const auto n = static_cast<Eigen::Index>(x.size() / 2);
  if (n == 0) return false;
  const Eigen::Map<const Eigen::Array2Xd> start(x0.data(), 2, n), end(x.data(), 2, n);
  const Eigen::Array2d lo = start.rowwise().minCoeff().min(end.rowwise().minCoeff()) - grow;
  const Eigen::Array2d hi = start.rowwise().maxCoeff().max(end.rowwise().maxCoeff()) + grow;
  if (!lo.allFinite() || !hi.allFinite()) return true;  // the per-particle passes deal with it
  for (const Collider& c : colliders) {
    Eigen::Vector2d cLo, cHi;
    if (!c.bounds(cLo, cHi)) return true;
    if ((lo <= cHi.array()).all() && (hi >= cLo.array()).all()) return true;
  }
  return false;
}
}  // namespace

int ParticleSystem::collideOver(const Eigen::VectorXd& x0, const Eigen::VectorXd& v0, double dt) {
  if (collidable_.size() < 2 && edges_.empty() &&
      !pathsMayReachColliders(colliders_, x0, x_, radius_.size() > 0 ? radius_.maxCoeff() + contactSettings_.slop : 0.0)) {
    coupled_.resetWarmStart();
    return 0;
  }
  // Each particle's path over the interval runs from (x0, v0) to its state as
  // the integrator left it (contact_path.h).
  const StepStart start{x0, v0, dt};
  const bool discs = collidable_.size() > 1, walls = !colliders_.empty(), edges = walls && !edges_.empty();
  lastFree_ = x_;
  ContactCount counted;
  // Discs meet each other and the colliders in the order of their impacts.
  if (discs)
    counted += contacts_.resolve(collidable_, colliders_, start, inverseMass_, radius_, contactSettings_, true, x_,
                                  v_, &lastFree_);
  // Every other particle meets only the colliders, on its own, and only if
  // its path comes near one (as does an edge, only if one of its ends does).
  if (walls) {
    double margin = radius_.size() > 0 ? radius_.maxCoeff() + contactSettings_.slop : 0.0;
    if (edges) margin = std::max(margin, edgeReach(edges_, x0, x_));
    markNearColliders(colliders_, x0, x_, margin, near_, nearList_);
    if (discs) {
      // Discs are resolved with each other, not here (their edges are tested below).
      for (int i : collidable_) near_[i] = 0;
      nearList_.erase(std::remove_if(nearList_.begin(), nearList_.end(), [&](int i) { return !near_[i]; }),
                      nearList_.end());
    }
    // Constrained particles that touch a collider, with every particle joined
    // to them by constraints, are resolved together with those constraints
    // (coupled_contacts.h); the rest each on their own.
    const std::vector<int>* singles = &nearList_;
    const bool coupled = coupleContacts_ && !constraints_.empty();
    if (coupled) {
      touching_.clear();
      for (int i : nearList_)
        if (touchesCollider(colliders_, x0.segment<2>(2 * i), x_.segment<2>(2 * i), radius_[i], contactSettings_.slop))
          touching_.push_back(i);
      const std::vector<int>& island = coupled_.island(constraints_, size(), structureStamp_, touching_);
      singles_.clear();
      std::set_difference(nearList_.begin(), nearList_.end(), island.begin(), island.end(),
                          std::back_inserter(singles_));
      singles = &singles_;
    }
    counted += resolveColliderContacts(colliders_, start, inverseMass_, radius_, contactSettings_, x_, v_,
                                        lastFree_, singles);
    if (coupled) {
      const CoupledSolveStats solved = coupled_.solve(constraints_, colliders_, start, mass_, inverseMass_, radius_,
                                                      contactSettings_, x_, v_);
      for (int i : coupled_.lastIsland()) lastFree_.segment<2>(2 * i) = x_.segment<2>(2 * i);
      contactStats_.contactIterations += solved.iterations;
      contactStats_.contactResidual = std::max(contactStats_.contactResidual, solved.residual);
      counted.contacts += solved.contacts;
    }
    if (edges) {
      edgeIncidence_.update(edges_, size(), structureStamp_);
      edgeIncidence_.mark(nearList_);
      if (discs) edgeIncidence_.mark(collidable_);
      edgeIncidence_.takeMarked(nearEdges_);
    }
  }
  const int edgeContacts =
      edges ? resolveEdgeContacts(colliders_, edges_, start, inverseMass_, radius_, x_, v_, lastFree_, &nearEdges_) : 0;
  counted.contacts += edgeContacts;
  // Resting contacts push on each other (a stack on a floor, a rope over a
  // nail): Gauss–Seidel passes until none is left, colliders last, as the
  // hard boundary. Without discs left touching or an edge caught, nothing
  // was pushed after the continuous passes and no pass is needed.
  // A pass ends the iteration when it changes no speed by more than would
  // move a particle by the slop in a step.
  const double settled = contactSettings_.slop / dt;
  const bool pushed = (discs && contacts_.touchingPairs() > 0) || edgeContacts > 0;
  const int passes = pushed ? contactSettings_.iterations : 0;
  for (int pass = 0; pass < passes; ++pass) {
    double largest = 0.0;
    int resolved = 0;
    if (discs) largest = contacts_.resolveResting(inverseMass_, radius_, contactSettings_, pass % 2 == 0, x_, v_);
    if (edges) resolved += resolveEdgeContacts(colliders_, edges_, start, inverseMass_, radius_, x_, v_, lastFree_, &nearEdges_);
    if (walls) {
      const ContactCount pushedOut =
          pushOutOfColliders(colliders_, inverseMass_, radius_, contactSettings_, x_, v_, lastFree_);
      resolved += pushedOut.contacts;
      counted.capped += pushedOut.capped;
    }
    if (largest <= settled && resolved == 0) break;
  }
  // A particle that ran out of the impact work cap was stopped short of its
  // motion: the step reports it as failed rather than lose the motion silently.
  if (counted.capped > 0 && contactStats_.failure == StepFailure::None)
    contactStats_.failure = StepFailure::ContactCapReached;
  contactsLastStep_ += counted.contacts;
  return counted.contacts;
}

double ParticleSystem::kineticEnergy() const {
  double e = 0.0;
  for (int i = 0; i < size(); ++i)
    if (inverseMass_[i] > 0.0) e += 0.5 * mass_[i] * v_.segment<2>(2 * i).squaredNorm();
  return e;
}

double ParticleSystem::potentialEnergy() const {
  const Phase s = phase();
  double e = 0.0;
  for (const auto& force : forces_)
    if (force->hasPotential()) e += force->potential(s);
  return e;
}

double ParticleSystem::maxConstraintError() const {
  const Phase s = phase();
  double worst = 0.0;
  for (const auto& c : constraints_) worst = std::max(worst, c->violation(s));
  return worst;
}

double ParticleSystem::maxRelativeConstraintError() const {
  const Phase s = phase();
  double worst = 0.0;
  for (const auto& c : constraints_)
    if (c->lengthScale() > 0.0) worst = std::max(worst, c->violation(s) / c->lengthScale());
  return worst;
}

bool ParticleSystem::finite() const { return x_.allFinite() && v_.allFinite(); }

}  // namespace particles

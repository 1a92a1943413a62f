#include "particles/particle_system.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "collision/contact_pass.h"
#include "collision/islands.h"
#include "parallel_for.h"
#include "particles/check.h"
#include "particles/forces/angular_spring.h"
#include "forces/force_batch.h"
#include "particles/forces/spring.h"
#include "particles/tearing.h"
#include "particles/threads.h"
#include "system_internals.h"

namespace particles {

struct ParticleSystem::Impl {
  ForceBatches batches;  // forces_ as flat arrays, rebuilt on a structure change
  Tearing tearing;
  ThreadUse threadUse;
};

ParticleSystem::ParticleSystem()
    : impl_(std::make_unique<Impl>()), contacts_(std::make_unique<ContactPass>()),
      islands_(std::make_unique<Islands>()) {}
ParticleSystem::~ParticleSystem() = default;
ParticleSystem::ParticleSystem(ParticleSystem&&) noexcept = default;
ParticleSystem& ParticleSystem::operator=(ParticleSystem&&) noexcept = default;

TearSettings& ParticleSystem::tearing() { return impl_->tearing.settings; }
const TearSettings& ParticleSystem::tearing() const { return impl_->tearing.settings; }
int ParticleSystem::tornLastStep() const { return impl_->tearing.tornLastStep(); }
ThreadUseSettings& ParticleSystem::threadUse() { return impl_->threadUse.settings; }
const ThreadUseSettings& ParticleSystem::threadUse() const { return impl_->threadUse.settings; }
ThreadUse& SystemInternals::threadUse(ParticleSystem& system) { return system.impl_->threadUse; }
ContactSettings& ParticleSystem::contactSettings() { return contacts_->settings(); }
const ContactSettings& ParticleSystem::contactSettings() const { return contacts_->settings(); }
bool ParticleSystem::colliding() const { return contactScene().colliding(); }
int ParticleSystem::contactsLastStep() const { return contacts_->contactsThisStep(); }
int ParticleSystem::sleeping() const { return islands_->sleeping(); }
void ParticleSystem::wake() { islands_->wakeAll(); }
// The contact pass sees a sleeping particle as pinned (islands.h).
ContactScene ParticleSystem::contactScene() const {
  return {colliders_, edges_, collidable_, constraints_, mass_, islands_->inverseMasses(inverseMass_), radius_,
          structureStamp_};
}

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
  wake();
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
  wake();
}

void ParticleSystem::setPinned(int i, bool pin) {
  requireIndex("setPinned", i, size());
  inverseMass_[i] = pin ? 0.0 : 1.0 / mass_[i];
  structureStamp_ = nextStructureStamp();
  wake();
  if (pin) v_.segment<2>(2 * i).setZero();
}

void ParticleSystem::setCollidable(int i, double radius) {
  requireIndex("setCollidable", i, size());
  requirePositive("particle radius", radius);
  if (radius_[i] == 0.0) collidable_.push_back(i);
  radius_[i] = radius;
  wake();
}

Force& ParticleSystem::addForce(std::unique_ptr<Force> force) {
  for (int i : force->particles()) requireIndex(force->type(), i, size());
  if (force->timeDependent()) {
    force->setTime(time_);
    clocked_.push_back(force.get());
  }
  forces_.push_back(std::move(force));
  structureStamp_ = nextStructureStamp();
  wake();
  return *forces_.back();
}

Constraint& ParticleSystem::addConstraint(std::unique_ptr<Constraint> constraint) {
  for (int i : constraint->particles()) requireIndex(constraint->type(), i, size());
  constraints_.push_back(std::move(constraint));
  structureStamp_ = nextStructureStamp();
  wake();
  solver_.resetWarmStart();
  return *constraints_.back();
}

void ParticleSystem::addCollider(const Collider& collider) {
  collider.validate();
  colliders_.push_back(collider);
  wake();
}

void ParticleSystem::addCollisionEdge(int a, int b) {
  requireIndex("collision edge", a, size());
  requireIndex("collision edge", b, size());
  if (a == b) throw std::invalid_argument("collision edge joins particle " + std::to_string(a) + " to itself");
  edges_.push_back({a, b});
  structureStamp_ = nextStructureStamp();
  wake();
}

void ParticleSystem::removeForce(const Force* force) {
  clocked_.erase(std::remove(clocked_.begin(), clocked_.end(), force), clocked_.end());
  forces_.erase(std::remove_if(forces_.begin(), forces_.end(),
                               [&](const std::unique_ptr<Force>& f) { return f.get() == force; }),
                forces_.end());
  structureStamp_ = nextStructureStamp();
  wake();
}

void ParticleSystem::setSpringEnabled(const Force* spring, bool enabled) {
  const auto found = std::find_if(forces_.begin(), forces_.end(),
                             [&](const std::unique_ptr<Force>& f) { return f.get() == spring; });
  Force* force = found == forces_.end() ? nullptr : found->get();
  bool* flag = nullptr;
  if (auto* asSpring = dynamic_cast<SpringForce*>(force)) flag = &asSpring->enabled_;
  if (auto* asAngle = dynamic_cast<AngularSpringForce*>(force)) flag = &asAngle->enabled_;
  if (!flag) throw std::invalid_argument("setSpringEnabled: not a spring or angle spring of this system");
  if (*flag == enabled) return;
  *flag = enabled;
  structureStamp_ = nextStructureStamp();
  wake();
}

int ParticleSystem::breakLinks(const std::vector<std::array<int, 2>>& links) {
  if (links.empty()) return 0;
  // The links that break with these (a torn face's diagonals), and with
  // those, until no force adds one more.
  std::vector<std::array<int, 2>> all = links;
  for (std::size_t known = 0; known != all.size();) {
    known = all.size();
    const LinkSet so(all);
    std::vector<std::array<int, 2>> more;
    for (const auto& force : forces_) force->linksBreakingWith(so, more);
    const LinkSet added(more);  // sorted and each once: a link two faces share counts once
    for (std::size_t k = 0; k < added.links().size(); ++k)
      if ((k == 0 || added.links()[k] != added.links()[k - 1]) && !so.contains(added.links()[k][0], added.links()[k][1]))
        all.push_back(added.links()[k]);
  }
  const LinkSet broken(all);
  int changed = 0;
  for (const auto& force : forces_) changed += force->dropLinks(broken);
  edges_.erase(std::remove_if(edges_.begin(), edges_.end(),
                              [&](const CollisionEdge& e) { return broken.contains(e.a, e.b); }),
               edges_.end());
  brokenLinks_.insert(brokenLinks_.end(), broken.links().begin(), broken.links().end());
  structureStamp_ = nextStructureStamp();
  wake();
  return changed;
}

void ParticleSystem::restore(const Snapshot& s) {
  if (s.x.size() != x_.size() || s.v.size() != v_.size())
    throw std::invalid_argument("snapshot was taken of a system of another size");
  x_ = s.x;
  v_ = s.v;
  time_ = s.time;
  wake();
  for (Force* force : clocked_) force->setTime(time_);
  solver_.resetWarmStart();
  contacts_->resetWarmStart();
}

namespace {
void requireStateSize(const char* what, const Eigen::VectorXd& given, const Eigen::VectorXd& held) {
  if (given.size() != held.size())
    throw std::invalid_argument(std::string(what) + " has " + std::to_string(given.size()) +
                                " values, the system " + std::to_string(held.size()) + " (2 per particle)");
}
}  // namespace

void ParticleSystem::setPositions(const Eigen::VectorXd& x) {
  requireStateSize("setPositions", x, x_);
  x_ = x;
  wake();
}

void ParticleSystem::setVelocities(const Eigen::VectorXd& v) {
  requireStateSize("setVelocities", v, v_);
  v_ = v;
  wake();
}

void ParticleSystem::setPosition(int i, const Eigen::Vector2d& p) {
  requireIndex("setPosition", i, size());
  x_.segment<2>(2 * i) = p;
  wake();
}

void ParticleSystem::setVelocity(int i, const Eigen::Vector2d& v) {
  requireIndex("setVelocity", i, size());
  v_.segment<2>(2 * i) = v;
  wake();
}

void ParticleSystem::acceleration(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& a) {
  SystemInternals::acceleration(*this, x, v, a, {});
}

void SystemInternals::acceleration(ParticleSystem& system, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                   Eigen::VectorXd& a, const ParticleRange& then) {
  ForceBatches& batches = system.impl_->batches;
  const Phase s = system.phase(x, v);
  batches.update(system.forces_, system.structureStamp_);
  ++system.evaluations_.forceEvaluations;
  if (system.constraints_.empty()) {  // nothing is added to f after the forces
    batches.applyAndDivide(s, system.f_, a, then);
    return;
  }
  batches.apply(s, system.f_);
  {
    system.solver_.addConstraintForces(s, system.constraints_, system.f_);
    const SolveStats& solve = system.solver_.stats();
    StepStats one{};
    one.solves = 1;
    one.cgIterations = solve.iterations;
    one.maxResidual = solve.residual;
    one.factorizations = solve.factorizations;
    one.directFallbacks = solve.directFallback;
    one.internalSteps = 0;
    if (solve.failed) one.failure = StepFailure::SolveFailed;
    system.evaluations_ += one;
  }
  // a = W f and then, range by range in one pass.
  a.resize(x.size());
  parallelRanges(system.size(), threadCount(), kParallelParticles, [&](int begin, int end) {
    for (int i = begin; i < end; ++i) a.segment<2>(2 * i) = system.inverseMass_[i] * system.f_.segment<2>(2 * i);
    if (then) then(begin, end);
  });
}

void SystemInternals::accelerations(ParticleSystem& system, const std::vector<StatePoint>& points,
                                    Eigen::VectorXd& a, const StageRange& then) {
  const int count = static_cast<int>(points.size());
  if (!system.constraints_.empty()) {  // a solve between the forces and a: evaluations one by one
    for (int k = 0; k < count; ++k)
      acceleration(system, points[k].x, points[k].v, a, stagePass(then, k));
    return;
  }
  ForceBatches& batches = system.impl_->batches;
  batches.update(system.forces_, system.structureStamp_);
  system.evaluations_.forceEvaluations += count;
  std::vector<Phase> phases;
  phases.reserve(points.size());
  for (const StatePoint& point : points) phases.push_back(system.phase(point.x, point.v));
  batches.applyAndDivide(phases, system.f_, a, then);
}

void ParticleSystem::appliedForces(const Eigen::VectorXd& x, const Eigen::VectorXd& v, Eigen::VectorXd& f) {
  impl_->batches.update(forces_, structureStamp_);
  impl_->batches.apply(phase(x, v), f);
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
  // Begin: settings are public fields, checked before anything moves, so a
  // bad value never leaves a step half done.
  evaluations_ = StepStats{};
  solver_.settings.validate();
  impl_->tearing.settings.validate();
  impl_->threadUse.settings.validate();
  const int threads = impl_->threadUse.begin(threadCount(), structureStamp_);
  const ThreadCountScope scope(threads);
  const long long regions = parallelRegions();
  for (Force* force : clocked_) force->setTime(time_);
  const ContactScene scene = contactScene();
  const bool awake = !islands_->allAsleep();
  const bool collideAfter = awake && scene.colliding() && !integrator.collidesInSubsteps();
  contacts_->beginStep(scene, x_, v_, collideAfter);
  StepStats stats{};  // with everything asleep: one step in which nothing moved
  if (awake) {
    // Integrate (sleeping particles are held where they fell asleep).
    stats = integrator.step(*this, dt);
    addEvaluationStats(stats);  // evaluations the integrator left in the tally
    islands_->hold(x_, v_);
    // Collide.
    if (collideAfter) contacts_->collideStep(scene, dt, ContactCoupling{true}, x_, v_);
    stats += contacts_->stepStats();
    // Sleep: islands at rest fall asleep; what an awake particle touched wakes.
    if (scene.colliding())
      islands_->update({forces_, constraints_, contacts_->lastContacts(), inverseMass_, structureStamp_},
                       contactSettings(), x_, v_, dt);
  }
  stats.sleeping = islands_->sleeping();
  // Tear: springs stretched past the limit break, decided once from the
  // step's end state, so every stage of the next step sees the same springs.
  impl_->tearing.tear(*this);
  // Advance the clock.
  time_ += dt;
  const bool parallel = parallelRegions() > regions;
  impl_->threadUse.end(parallel);
  stats.threads = parallel ? threads : 1;
  lastStepStats_ = stats;
  return stats;
}

int ParticleSystem::collideOver(const Eigen::VectorXd& x0, const Eigen::VectorXd& v0, double dt,
                                const PathBounds* paths) {
  islands_->hold(x_, v_);
  return contacts_->collide(contactScene(), StepStart{x0, v0, dt, paths}, ContactCoupling{true}, x_, v_);
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

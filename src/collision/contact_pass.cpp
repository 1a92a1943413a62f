#include "contact_pass.h"

#include <algorithm>
#include <Eigen/Dense>

#include "boundary_guard.h"
#include "narrow_phase.h"
#include "parallel_for.h"
#include "particles/check.h"
#include "particles/threads.h"

namespace particles {

void ContactSettings::validate() const {
  if (maxImpacts < 1 || maxImpacts > 1000000000)
    throw std::invalid_argument("contact maxImpacts must be in [1, 1000000000], got " + std::to_string(maxImpacts));
  requireNonNegative("contact slop", slop);
  if (coupledIterations < 1 || coupledIterations > 100000)
    throw std::invalid_argument("contact coupledIterations must be in [1, 100000], got " +
                                std::to_string(coupledIterations));
  if (positionIterations < 1 || positionIterations > 100000)
    throw std::invalid_argument("contact positionIterations must be in [1, 100000], got " +
                                std::to_string(positionIterations));
  requireNonNegative("contact coupledTolerance", coupledTolerance);
  requireNonNegative("contact restitutionThreshold", restitutionThreshold);
  requireInRange("particle contact restitution", particleRestitution, 0.0, 1.0);
  requireNonNegative("particle contact friction", particleFriction);
  requireNonNegative("contact sleepSpeed", sleepSpeed);
  requireNonNegative("contact sleepTime", sleepTime);
}

namespace {
// Every straight path a contact sweeps (particle or edge, from x0 to x) lies
// in the box around all of x0 and x grown by the largest radius and the slop:
// when that box meets no collider's bounds (a half-plane has none), no sweep
// can hit, and a substep's collision pass over a cloth far from the walls
// costs one pass over the positions and radii (or none, when the caller
// measured the box in a pass of its own).
PathBounds measurePaths(const Eigen::VectorXd& x0, const Eigen::VectorXd& x, const Eigen::VectorXd& radius) {
  const int n = static_cast<int>(x.size() / 2);
  const std::vector<PathBounds> parts =
      parallelRangeResults<PathBounds>(n, threadCount(), kParallelEntries / 2, [&](int begin, int end) {
        return PathBounds::of(x0.data(), x.data(), radius.data(), begin, end);
      });
  PathBounds all;
  for (const PathBounds& part : parts) all.merge(part);
  return all;
}

bool pathsMayReachColliders(const std::vector<Collider>& colliders, const PathBounds& paths, double slop) {
  if (!paths.finite) return true;            // the per-particle passes deal with it
  if (paths.lo[0] > paths.hi[0]) return false;  // no particle
  const double grow = paths.radius + slop;
  const Eigen::Array2d lo = Eigen::Array2d(paths.lo[0], paths.lo[1]) - grow,
                       hi = Eigen::Array2d(paths.hi[0], paths.hi[1]) + grow;
  for (const Collider& c : colliders) {
    Eigen::Vector2d cLo, cHi;
    if (!c.bounds(cLo, cHi)) return true;
    if ((lo <= cHi.array()).all() && (hi >= cLo.array()).all()) return true;
  }
  return false;
}

// Solves after the first that a step may make for contacts the solve ran into.
constexpr int kSolveRounds = 3;
// The most pairs of discs a step takes on: 64 a disc (a disc among equal
// discs touches six; the grid's cells, grown by the step's travel, hold more
// candidates), and never fewer than a million (mixed radii).
constexpr std::size_t kPairsPerDisc = 64;
constexpr std::size_t kPairsAtLeast = 1 << 20;

double largestRadius(const Eigen::VectorXd& radius) { return radius.size() > 0 ? radius.maxCoeff() : 0.0; }
}  // namespace

void ContactPass::beginStep(const ContactScene& scene, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                            bool keepStart) {
  if (scene.colliding()) settings_.validate();
  if (keepStart) {
    startX_ = x;
    startV_ = v;
  }
  stats_ = StepStats{};
  stats_.internalSteps = 0;
  contacts_ = 0;
}

int ContactPass::collideStep(const ContactScene& scene, double dt, const ContactCoupling& coupling,
                             Eigen::VectorXd& x, Eigen::VectorXd& v) {
  return collide(scene, StepStart{startX_, startV_, dt}, coupling, x, v);
}

int ContactPass::collide(const ContactScene& scene, const StepStart& start, const ContactCoupling& coupling,
                         Eigen::VectorXd& x, Eigen::VectorXd& v) {
  const bool discs = scene.discs.size() > 1;
  if (!discs && scene.edges.empty() &&
      !pathsMayReachColliders(scene.colliders,
                              start.paths != nullptr ? *start.paths : measurePaths(start.x, x, scene.radius),
                              settings_.slop)) {
    found_.clear();
    solver_.resetWarmStart();
    return 0;
  }
  // 1. Broad phase.
  broadPhase(scene, start, x);
  if (pairsCapped_) {  // more pairs of discs than a step resolves: failed, not run for hours
    stats_.failure = StepFailure::ContactCapReached;
    return 0;
  }
  // 2. Impacts: what moves alone bounces at its exact times.
  refs_.reset(start);
  sortMovers(scene, x, v);
  ContactCount counted = impacts_.resolve(scene.colliders, points_, moverDiscs_, moverPairs_, anchored_, start,
                                          scene.inverseMass, scene.radius, settings_, x, v, refs_);
  // 3. Narrow phase: every contact at the step's end.
  found_.clear();
  const NarrowInput narrow{scene.colliders, start, refs_, scene.inverseMass, scene.radius, settings_, solver_};
  if (!scene.colliders.empty()) colliderContacts(narrow, nearList_, x, v, found_);
  if (discs) discPairContacts(narrow, scene.discs, discPairs_, x, v, found_);
  if (!nearEdges_.empty()) edgeCornerContacts(narrow, scene.edges, nearEdges_, x, v, found_);
  // 4. Solve: the contacts and the constraints that hold their particles.
  const ContactSolveInput input{scene.constraints, scene.mass, scene.inverseMass, refs_, coupling.withConstraints};
  if (!found_.empty()) {
    freeX_ = x;
    freeV_ = v;
  }
  ContactSolveStats solved = solver_.solve(found_, input, scene.structure, settings_, x, v);
  // Contacts the solve ran into (a particle slid along one collider into
  // another) join, and the solve starts again from the free state.
  for (int round = 0; round < kSolveRounds && !found_.empty(); ++round) {
    const std::vector<int> moved = solver_.lastParticles();
    if (missedContacts(narrow, moved, scene.discs, discPairs_, x, freeV_, found_) == 0) break;
    for (const int p : moved) {
      x.segment<2>(2 * p) = freeX_.segment<2>(2 * p);
      v.segment<2>(2 * p) = freeV_.segment<2>(2 * p);
    }
    solved = solver_.solve(found_, input, scene.structure, settings_, x, v);
  }
  stats_.contactIterations += solved.iterations;
  stats_.contactResidual = std::max(stats_.contactResidual, solved.residual);
  counted.contacts += static_cast<int>(found_.size());
  // 5. Guards: the colliders are a hard boundary.
  counted += guard(scene, start, x, v);
  if (counted.capped > 0 && stats_.failure == StepFailure::None) stats_.failure = StepFailure::ContactCapReached;
  contacts_ += counted.contacts;
  return counted.contacts;
}

void ContactPass::broadPhase(const ContactScene& scene, const StepStart& start, const Eigen::VectorXd& x) {
  const bool walls = !scene.colliders.empty(), edges = walls && !scene.edges.empty();
  nearList_.clear();
  nearEdges_.clear();
  pairsCapped_ = false;
  if (walls) {
    double margin = largestRadius(scene.radius) + settings_.slop;
    if (edges) margin = std::max(margin, edgeReach(scene.edges, start.x, x));
    markNearColliders(scene.colliders, start.x, x, margin, near_, nearList_);
  }
  discPairs_.clear();
  if (scene.discs.size() > 1) {
    // A disc stays within twice its free travel of its start (impacts turn
    // it, and between comparable masses do not much speed it up), so any
    // pair that touches during the step lies in neighbouring cells.
    double maxRadius = 0.0, maxTravel = 0.0;
    for (int i : scene.discs) {
      maxRadius = std::max(maxRadius, scene.radius[i]);
      maxTravel = std::max(maxTravel, (x.segment<2>(2 * i) - start.x.segment<2>(2 * i)).norm());
    }
    const std::size_t cap = std::max<std::size_t>(kPairsPerDisc * scene.discs.size(), kPairsAtLeast);
    pairsCapped_ = !grid_.findPairs(scene.discs, start.x, 2.0 * (maxRadius + 2.0 * maxTravel), discPairs_, cap);
  }
  if (edges) {
    edgeIncidence_.update(scene.edges, static_cast<int>(scene.mass.size()), scene.structure);
    edgeIncidence_.mark(nearList_);
    edgeIncidence_.takeMarked(nearEdges_);
  }
}

// The particles that move alone take the impacts stage: those in no
// constraint and those held only by constraints whose other particles are
// pinned (with the projector onto what their constraints leave them, from
// the constraints' gradients at the step's end) — the points near a collider,
// every such disc, and the pairs among those discs.
void ContactPass::sortMovers(const ContactScene& scene, const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
  const int n = static_cast<int>(scene.mass.size());
  if (moversStructure_ != scene.structure || static_cast<int>(alone_.size()) != n) {
    alone_.assign(n, Alone::Free);
    for (const auto& c : scene.constraints)
      for (int p : c->particles()) {
        bool anchored = true;
        for (int q : c->particles())
          if (q != p && scene.inverseMass[q] != 0.0) anchored = false;
        if (!anchored) alone_[p] = Alone::Held;
        else if (alone_[p] == Alone::Free) alone_[p] = Alone::Anchored;
      }
    constraintsOf_.assign(n, {});
    for (int k = 0; k < static_cast<int>(scene.constraints.size()); ++k)
      for (int p : scene.constraints[k]->particles())
        if (alone_[p] == Alone::Anchored) constraintsOf_[p].push_back(k);
    moversStructure_ = scene.structure;
  }
  points_.clear();
  for (int i : nearList_)
    if (scene.radius[i] == 0.0 && alone_[i] != Alone::Held) points_.push_back(i);
  moverDiscs_.clear();
  moverPairs_.clear();
  moverIndex_.assign(scene.discs.size(), -1);
  for (std::size_t a = 0; a < scene.discs.size(); ++a)
    if (alone_[scene.discs[a]] != Alone::Held) {
      moverIndex_[a] = static_cast<int>(moverDiscs_.size());
      moverDiscs_.push_back(scene.discs[a]);
    }
  for (const auto& [a, b] : discPairs_)
    if (moverIndex_[a] >= 0 && moverIndex_[b] >= 0) moverPairs_.emplace_back(moverIndex_[a], moverIndex_[b]);
  anchored_.clear();
  const auto anchor = [&](int p) {
    if (alone_[p] != Alone::Anchored) return;
    // P = I − Jᵀ (J Jᵀ)⁻¹ J over the particle's rows of its constraints' J.
    Eigen::Matrix<double, Eigen::Dynamic, 2> J(constraintsOf_[p].size(), 2);
    for (std::size_t k = 0; k < constraintsOf_[p].size(); ++k) {
      const Constraint& c = *scene.constraints[constraintsOf_[p][k]];
      std::vector<Eigen::Vector2d> blocks(c.particles().size()), dots(c.particles().size());
      ConstraintRow row{0.0, 0.0, blocks.data(), dots.data()};
      c.evaluate(Phase{x, v, scene.mass, scene.inverseMass}, row);
      const auto at = std::find(c.particles().begin(), c.particles().end(), p) - c.particles().begin();
      J.row(static_cast<Eigen::Index>(k)) = blocks[at].transpose();
    }
    const Eigen::Matrix2d held = J.transpose() * J;
    Eigen::Matrix2d P = Eigen::Matrix2d::Identity();
    if (held.trace() > 0.0) P -= J.transpose() * (J * J.transpose()).completeOrthogonalDecomposition().solve(J);
    anchored_.push_back({p, P});
  };
  for (int p : points_) anchor(p);
  for (int p : moverDiscs_) anchor(p);
  std::sort(anchored_.begin(), anchored_.end(), [](const Anchored& a, const Anchored& b) { return a.particle < b.particle; });
}

// Stage 5: whatever the solve left inside a collider (its caps reached) is
// put back on the face it entered; no edge is left across a capsule's or a
// disc's core.
ContactCount ContactPass::guard(const ContactScene& scene, const StepStart& start, Eigen::VectorXd& x,
                                Eigen::VectorXd& v) {
  ContactCount counted;
  if (scene.colliders.empty()) return counted;
  lastFree_ = refs_.x;
  counted.contacts += pushOutOfColliders(scene.colliders, solver_.lastParticles(), scene.inverseMass, scene.radius,
                                         settings_, x, v, lastFree_, counted.capped);
  if (!nearEdges_.empty()) {
    counted.contacts += holdEdgeEndsOffCapsules(scene.colliders, scene.edges, start, scene.inverseMass,
                                                scene.radius, x, v, lastFree_, nearEdges_);
    counted.contacts += holdEdgesOffCores(scene.colliders, scene.edges, start, scene.inverseMass, scene.radius, x, v,
                                          lastFree_, nearEdges_);
  }
  return counted;
}

}  // namespace particles

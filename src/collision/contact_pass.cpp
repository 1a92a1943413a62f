#include "contact_pass.h"

#include "collider_broad_phase.h"
#include "collider_contacts.h"
#include "edge_contacts.h"

#include <algorithm>
#include <iterator>

#include "parallel_for.h"
#include "particles/check.h"
#include "particles/threads.h"

namespace particles {

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
  const bool discs = scene.discs.size() > 1, walls = !scene.colliders.empty();
  if (!discs && scene.edges.empty() &&
      !pathsMayReachColliders(scene.colliders,
                              start.paths != nullptr ? *start.paths : measurePaths(start.x, x, scene.radius),
                              settings_.slop)) {
    coupled_.resetWarmStart();
    return 0;
  }
  lastFree_ = x;
  ContactCount counted;
  // 1. Discs meet each other and the colliders in the order of their impacts.
  if (discs)
    counted += discs_.resolve(scene.discs, scene.colliders, start, scene.inverseMass, scene.radius, settings_, true,
                              x, v, &lastFree_);
  // 2–3. Every other particle meets only the colliders, and only if its path
  // comes near one (as does an edge, only if one of its ends does).
  if (walls) counted += collideWalls(scene, start, coupling, x, v);
  // 4. Edges against the colliders' corners and cores.
  const bool edges = walls && !scene.edges.empty();
  const int edgeContacts = edges ? resolveEdgeContacts(scene.colliders, scene.edges, start, scene.inverseMass,
                                                       scene.radius, x, v, lastFree_, &nearEdges_)
                                 : 0;
  counted.contacts += edgeContacts;
  // 5. Resting contacts push on each other.
  counted += restingPasses(scene, start, edgeContacts > 0, x, v);
  // 6. No edge is left cut through the core of a capsule or a disc.
  if (edges)
    counted.contacts += holdEdgesOffCores(scene.colliders, scene.edges, start, scene.inverseMass, scene.radius, x, v,
                                          lastFree_, nearEdges_);
  if (counted.capped > 0 && stats_.failure == StepFailure::None) stats_.failure = StepFailure::ContactCapReached;
  contacts_ += counted.contacts;
  return counted.contacts;
}

ContactCount ContactPass::collideWalls(const ContactScene& scene, const StepStart& start,
                                       const ContactCoupling& coupling, Eigen::VectorXd& x, Eigen::VectorXd& v) {
  const bool discs = scene.discs.size() > 1, edges = !scene.edges.empty();
  const auto particles = static_cast<int>(scene.mass.size());
  double margin = largestRadius(scene.radius) + settings_.slop;
  if (edges) margin = std::max(margin, edgeReach(scene.edges, start.x, x));
  markNearColliders(scene.colliders, start.x, x, margin, near_, nearList_);
  if (discs) {
    // Discs are resolved with each other, not here (their edges are tested later).
    for (int i : scene.discs) near_[i] = 0;
    nearList_.erase(std::remove_if(nearList_.begin(), nearList_.end(), [&](int i) { return !near_[i]; }),
                    nearList_.end());
  }
  // Constrained particles that touch a collider, with every particle joined
  // to them by constraints, are resolved together with those constraints;
  // the rest each on their own.
  const std::vector<int>* singles = &nearList_;
  const bool coupled = coupling.withConstraints && !scene.constraints.empty();
  if (coupled) {
    touching_.clear();
    for (int i : nearList_)
      if (touchesCollider(scene.colliders, start.x.segment<2>(2 * i), x.segment<2>(2 * i), scene.radius[i],
                          settings_.slop))
        touching_.push_back(i);
    const std::vector<int>& island = coupled_.island(scene.constraints, particles, scene.structure, touching_);
    singles_.clear();
    std::set_difference(nearList_.begin(), nearList_.end(), island.begin(), island.end(),
                        std::back_inserter(singles_));
    singles = &singles_;
  }
  ContactCount counted = resolveColliderContacts(scene.colliders, start, scene.inverseMass, scene.radius, settings_,
                                                 x, v, lastFree_, singles);
  if (coupled) {
    const CoupledSolveStats solved = coupled_.solve(scene.constraints, scene.colliders, start, scene.mass,
                                                    scene.inverseMass, scene.radius, settings_, coupling.drift, x, v);
    for (int i : coupled_.lastIsland()) lastFree_.segment<2>(2 * i) = x.segment<2>(2 * i);
    stats_.contactIterations += solved.iterations;
    stats_.contactResidual = std::max(stats_.contactResidual, solved.residual);
    counted.contacts += solved.contacts;
  }
  if (edges) {
    edgeIncidence_.update(scene.edges, particles, scene.structure);
    edgeIncidence_.mark(nearList_);
    if (discs) edgeIncidence_.mark(scene.discs);
    edgeIncidence_.takeMarked(nearEdges_);
  }
  return counted;
}

// Resting contacts push on each other (a stack on a floor, a rope over a
// nail): Gauss–Seidel passes until none is left, colliders last, as the hard
// boundary. Without discs left touching or an edge caught, nothing was pushed
// after the continuous passes and no pass is needed. A pass ends the
// iteration when it changes no speed by more than would move a particle by
// the slop in a step.
ContactCount ContactPass::restingPasses(const ContactScene& scene, const StepStart& start, bool edgesCaught,
                                        Eigen::VectorXd& x, Eigen::VectorXd& v) {
  const bool discs = scene.discs.size() > 1, walls = !scene.colliders.empty(), edges = walls && !scene.edges.empty();
  const double settled = settings_.slop / start.dt;
  const bool pushed = (discs && discs_.touchingPairs() > 0) || edgesCaught;
  const int passes = pushed ? settings_.iterations : 0;
  ContactCount counted;
  for (int pass = 0; pass < passes; ++pass) {
    double largest = 0.0;
    int resolved = 0;
    if (discs) largest = discs_.resolveResting(scene.inverseMass, scene.radius, settings_, pass % 2 == 0, x, v);
    if (edges)
      resolved += resolveEdgeContacts(scene.colliders, scene.edges, start, scene.inverseMass, scene.radius, x, v,
                                      lastFree_, &nearEdges_);
    if (walls) {
      const ContactCount pushedOut =
          pushOutOfColliders(scene.colliders, scene.inverseMass, scene.radius, settings_, x, v, lastFree_);
      resolved += pushedOut.contacts;
      counted.capped += pushedOut.capped;
    }
    if (largest <= settled && resolved == 0) break;
  }
  return counted;
}

}  // namespace particles

#pragma once
// The broad phase of the contact pass: the particles and collision edges whose
// paths over the step come near a collider, and the pairs of discs that may
// meet each other.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "particles/collider.h"
#include "particles/collision.h"

namespace particles {

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

// Pairs of discs near enough to meet this step: a uniform grid of cells of
// the given size over the discs' positions (hashed into 2·count buckets,
// discs sorted by bucket: linear time), each disc against the discs of its
// own and the eight neighbouring cells. A cell at least twice the largest
// radius plus twice the largest travel finds every pair that touches in the
// step. Cell coordinates are clamped, so a far-flung (or exploded) disc
// cannot overflow the integer conversion.
class DiscGrid {
 public:
  // pairs receives (a, b), a < b, indices into `discs`, each pair once,
  // ascending in a and then in the order of the grid. Returns false, with
  // the pairs found so far, when there are more than maxPairs (discs piled on
  // one point, or a cell grown by an exploding disc's travel): the work and
  // memory of a step stay linear in the discs.
  bool findPairs(const std::vector<int>& discs, const Eigen::VectorXd& x, double cell,
                 std::vector<std::pair<int, int>>& pairs,
                 std::size_t maxPairs = std::numeric_limits<std::size_t>::max());

 private:
  std::vector<Eigen::Vector2i> cells_;
  std::vector<int> bucket_, order_, bucketStart_, fill_;
};

// The largest side of an edge's box over the step (its two ends at x0 and
// x1): the margin markNearColliders needs for edges.
double edgeReach(const std::vector<CollisionEdge>& edges, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1);

}  // namespace particles

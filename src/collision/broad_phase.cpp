// The broad phase: which particles' paths over the step come near any
// collider at all, the collision edges at those particles, and the pairs of
// discs near each other.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "broad_phase.h"
#include "parallel_for.h"
#include "particles/threads.h"
#include "set_flags.h"

namespace particles {

namespace {

// Consecutive particles tested together first: a cloth's or a chain's
// neighbours are neighbours in index order, so a block's box is small and
// most blocks of a large system meet no collider.
constexpr int kBlock = 16;

// The box (lo x, lo y, hi x, hi y) of the paths of particles [first, last),
// or nothing when a coordinate is not finite (a NaN would make min and max
// drop values, so such a block is tested particle by particle).
std::optional<std::array<double, 4>> pathBox(const double* S, const double* X, int first, int last) {
  using Point = Eigen::Map<const Eigen::Array2d>;
  Eigen::Array2d lo = Eigen::Array2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  Eigen::Array2d sum = Eigen::Array2d::Zero();  // finite only if every coordinate is
  for (int i = first; i < last; ++i) {
    const Point s(S + 2 * i), x(X + 2 * i);
    lo = lo.min(s).min(x);
    hi = hi.max(s).max(x);
    sum += s + x;
  }
  if (!sum.allFinite()) return std::nullopt;
  return std::array<double, 4>{lo.x(), lo.y(), hi.x(), hi.y()};
}

// Up to kChunk colliders grown by the margin, on the stack: boxes (lo x,
// lo y, hi x, hi y) and half-plane rows (n, n·p + margin).
constexpr std::size_t kChunk = 8;
struct GrownChunk {
  std::array<std::array<double, 4>, kChunk> boxes{}, planes{};
  std::size_t boxCount = 0, planeCount = 0;

  GrownChunk(const std::vector<Collider>& colliders, std::size_t first, std::size_t last, double margin) {
    for (std::size_t k = first; k < last; ++k) {
      const Collider& c = colliders[k];
      Eigen::Vector2d lo, hi;
      if (c.bounds(lo, hi))
        boxes[boxCount++] = {lo.x() - margin, lo.y() - margin, hi.x() + margin, hi.y() + margin};
      else
        planes[planeCount++] = {c.normal.x(), c.normal.y(), c.normal.dot(c.points[0]) + margin, 0.0};
    }
  }

  // The block is apart when its box is apart from every collider. For a
  // half-plane the least n·x over the box is at its corner against n; n·x is
  // monotone in each coordinate in floating point too, so each particle's
  // n·a and n·b are at least that corner's.
  bool apart(const std::array<double, 4>& B) const {
    for (std::size_t k = 0; k < boxCount; ++k) {
      const std::array<double, 4>& b = boxes[k];
      if (!(B[1] > b[3] || B[3] < b[1] || B[0] > b[2] || B[2] < b[0])) return false;
    }
    for (std::size_t k = 0; k < planeCount; ++k) {
      const std::array<double, 4>& p = planes[k];
      if (!(p[0] * (p[0] >= 0.0 ? B[0] : B[2]) + p[1] * (p[1] >= 0.0 ? B[1] : B[3]) > p[2])) return false;
    }
    return true;
  }

  // Whether the path a → b comes within the margin of one of the colliders.
  bool near(double ax, double ay, double bx, double by) const {
    const double loX = std::min(ax, bx), hiX = std::max(ax, bx), loY = std::min(ay, by), hiY = std::max(ay, by);
    for (std::size_t k = 0; k < boxCount; ++k) {
      const std::array<double, 4>& b = boxes[k];
      if (loY <= b[3] && hiY >= b[1] && loX <= b[2] && hiX >= b[0]) return true;
    }
    // A half-plane n·(x − p) ≤ 0: near when either end is within margin of it.
    for (std::size_t k = 0; k < planeCount; ++k) {
      const std::array<double, 4>& p = planes[k];
      if (std::min(p[0] * ax + p[1] * ay, p[0] * bx + p[1] * by) <= p[2]) return true;
    }
    return false;
  }
};

}  // namespace

void markNearColliders(const std::vector<Collider>& colliders, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1,
                       double margin, std::vector<char>& near, std::vector<int>& nearList) {
  const int n = static_cast<int>(x1.size() / 2);
  near.assign(n, 0);
  nearList.clear();
  const double* S = x0.data();
  const double* X = x1.data();
  // Colliders in chunks; each particle's path box is made once per chunk and
  // tested with a few comparisons per collider. Blocks touch their own
  // particles only: any thread may test any block, with the same flags.
  const int blocks = (n + kBlock - 1) / kBlock;
  for (std::size_t first = 0; first < colliders.size(); first += kChunk) {
    const GrownChunk chunk(colliders, first, std::min(colliders.size(), first + kChunk), margin);
    parallelRanges(blocks, threadCount(), kParallelEntries / kBlock, [&](int firstBlock, int lastBlock) {
      for (int block = firstBlock * kBlock; block < std::min(n, lastBlock * kBlock); block += kBlock) {
        const int end = std::min(n, block + kBlock);
        const std::optional<std::array<double, 4>> box = pathBox(S, X, block, end);
        if (box && chunk.apart(*box)) continue;
        for (int i = block; i < end; ++i)
          if (!near[i]) near[i] = chunk.near(S[2 * i], S[2 * i + 1], X[2 * i], X[2 * i + 1]);
      }
    });
  }
  contact::appendSetFlags(near, nearList);
}

void EdgeIncidence::update(const std::vector<CollisionEdge>& edges, int particles, std::uint64_t structure) {
  if (structure_ == structure) return;
  structure_ = structure;
  first_.assign(particles + 1, 0);
  for (const CollisionEdge& e : edges) {
    ++first_[e.a + 1];
    ++first_[e.b + 1];
  }
  for (int p = 0; p < particles; ++p) first_[p + 1] += first_[p];
  ids_.resize(first_[particles]);
  std::vector<int> fill(first_.begin(), first_.end() - 1);
  for (int k = 0; k < static_cast<int>(edges.size()); ++k) {
    ids_[fill[edges[k].a]++] = k;
    ids_[fill[edges[k].b]++] = k;
  }
  marked_.assign(edges.size(), 0);
}

void EdgeIncidence::mark(const std::vector<int>& particles) {
  for (int p : particles)
    for (int k = first_[p]; k < first_[p + 1]; ++k) marked_[ids_[k]] = 1;
}

void EdgeIncidence::takeMarked(std::vector<int>& out) {
  // Edge contacts move particles one edge after another: the edge order is kept.
  out.clear();
  contact::appendSetFlags(marked_, out);
  for (int e : out) marked_[e] = 0;
}

bool DiscGrid::findPairs(const std::vector<int>& discs, const Eigen::VectorXd& x, double cell,
                         std::vector<std::pair<int, int>>& pairs, std::size_t maxPairs) {
  pairs.clear();
  const int count = static_cast<int>(discs.size());
  if (count < 2 || !(cell > 0.0) || !std::isfinite(cell)) return true;
  int buckets = 1;
  while (buckets < 2 * count) buckets <<= 1;
  auto toCell = [&](double coordinate) {
    const double c = std::floor(coordinate / cell);
    return static_cast<int>(std::isfinite(c) ? std::clamp(c, -1e9, 1e9) : 1e9);
  };
  auto bucketOf = [&](const Eigen::Vector2i& c) {
    const unsigned long long h = static_cast<unsigned long long>(c.x()) * 73856093ULL ^
                                 static_cast<unsigned long long>(c.y()) * 19349663ULL;
    return static_cast<int>(h & static_cast<unsigned long long>(buckets - 1));
  };
  cells_.resize(count);
  bucket_.resize(count);
  bucketStart_.assign(buckets + 1, 0);
  for (int a = 0; a < count; ++a) {
    const int i = discs[a];
    cells_[a] = Eigen::Vector2i(toCell(x[2 * i]), toCell(x[2 * i + 1]));
    bucket_[a] = bucketOf(cells_[a]);
    ++bucketStart_[bucket_[a] + 1];
  }
  for (int b = 0; b < buckets; ++b) bucketStart_[b + 1] += bucketStart_[b];
  order_.resize(count);
  fill_.assign(bucketStart_.begin(), bucketStart_.end() - 1);
  for (int a = 0; a < count; ++a) order_[fill_[bucket_[a]]++] = a;
  for (int a = 0; a < count; ++a)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const Eigen::Vector2i c = cells_[a] + Eigen::Vector2i(dx, dy);
        const int bucket = bucketOf(c);
        for (int s = bucketStart_[bucket]; s < bucketStart_[bucket + 1]; ++s) {
          const int b = order_[s];
          if (b > a && cells_[b] == c) pairs.emplace_back(a, b);  // each pair once; skip hash collisions
          if (pairs.size() > maxPairs) return false;
        }
      }
  return true;
}

double edgeReach(const std::vector<CollisionEdge>& edges, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1) {
  // Each side of an edge's box is at most the edge's extent along it at the
  // end plus the travel of its two ends: |x_i − x_j|∞ + 2 max_k |x1_k − x0_k|∞.
  // (Both axes at once; with a coordinate not finite the reach may be any value.)
  // Maxima, so the same on any thread count.
  const double* X = x1.data();
  const double* S = x0.data();
  const int threads = threadCount();
  const double extent = std::max(0.0, parallelMax(static_cast<int>(edges.size()), threads, kParallelEntries, [&](int k) {
    const CollisionEdge& e = edges[k];
    return std::max(std::abs(X[2 * e.a] - X[2 * e.b]), std::abs(X[2 * e.a + 1] - X[2 * e.b + 1]));
  }));
  const double travel = std::max(0.0, parallelMax(static_cast<int>(x1.size()), threads, kParallelEntries,
                                                  [&](int k) { return std::abs(X[k] - S[k]); }));
  return extent + 2.0 * travel;
}

}  // namespace particles

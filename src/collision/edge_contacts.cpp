// Collision edges (segments between two particles) against collider corners.
#include <algorithm>
#include <cmath>
#include <vector>

#include "contact_track.h"
#include "set_flags.h"
#include "particles/collision.h"

namespace particles {

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

int resolveEdgeContacts(const std::vector<Collider>& colliders, const std::vector<CollisionEdge>& edges,
                        const StepStart& start, const Eigen::VectorXd& inverseMass, Eigen::VectorXd& x,
                        Eigen::VectorXd& v, const std::vector<int>* candidates) {
  int contacts = 0;
  // Broad phase: a collider is tested against an edge only when their boxes
  // overlap (the edge's box spans its start and end, the collider's its
  // corners). A half-plane has no corner: its particles keep edges out.
  const contact::ColliderBoxes boxes(colliders);
  const int count = static_cast<int>(colliders.size());
  const double* X = x.data();
  const double* S = start.x.data();
  const int tested = candidates ? static_cast<int>(candidates->size()) : static_cast<int>(edges.size());
  for (int t = 0; t < tested; ++t) {
    const CollisionEdge& edge = edges[candidates ? (*candidates)[t] : t];
    const int i = edge.a, j = edge.b;
    const double wi = inverseMass[i], wj = inverseMass[j];
    if (wi + wj == 0.0) continue;
    const double loX = std::min(std::min(X[2 * i], X[2 * j]), std::min(S[2 * i], S[2 * j]));
    const double hiX = std::max(std::max(X[2 * i], X[2 * j]), std::max(S[2 * i], S[2 * j]));
    const double loY = std::min(std::min(X[2 * i + 1], X[2 * j + 1]), std::min(S[2 * i + 1], S[2 * j + 1]));
    const double hiY = std::max(std::max(X[2 * i + 1], X[2 * j + 1]), std::max(S[2 * i + 1], S[2 * j + 1]));
    for (int m = 0; m < count; ++m) {
      if (colliders[m].shape == ColliderShape::HalfPlane) continue;
      if (loX > boxes.hi[m].x() || hiX < boxes.lo[m].x() || loY > boxes.hi[m].y() || hiY < boxes.lo[m].y()) continue;
      const Collider& c = colliders[m];
      for (const Eigen::Vector2d& corner : c.points) {
        const Eigen::Vector2d xi = x.segment<2>(2 * i), xj = x.segment<2>(2 * j), e = xj - xi;
        const double length2 = e.squaredNorm();
        if (length2 == 0.0) continue;
        // b = the corner's place along the edge at the end; only the edge's interior can catch it.
        const double b = (corner - xi).dot(e) / length2;
        if (!(b > 0.0 && b < 1.0)) continue;
        // The side of the edge the corner was on at the start, σ = ±1.
        const Eigen::Vector2d si = start.x.segment<2>(2 * i), sj = start.x.segment<2>(2 * j);
        const double side0 = cross(sj - si, corner - si);
        if (side0 == 0.0) continue;
        const double sigma = side0 > 0.0 ? 1.0 : -1.0;
        // N: unit normal of the edge pointing away from the corner's side;
        // the edge point must stay at least r = c.radius beyond the corner.
        const Eigen::Vector2d left = Eigen::Vector2d(-e.y(), e.x()) / std::sqrt(length2);
        const Eigen::Vector2d N = -sigma * left;
        const double depth = c.radius + N.dot(corner - xi);  // > 0: the edge is at or past the corner
        if (!(depth > 0.0)) continue;
        // The edge point p = (1 − b) x_i + b x_j moves by depth along N with
        // the least mass-weighted change: Δx_k = N depth w_k β_k / Σ w β².
        const double bi = 1.0 - b, bj = b, k = wi * bi * bi + wj * bj * bj;
        x.segment<2>(2 * i) += (depth * wi * bi / k) * N;
        x.segment<2>(2 * j) += (depth * wj * bj / k) * N;
        // The same weights for the velocity: the edge point's approach is
        // removed (an inelastic hold), and its sliding limited by Coulomb.
        const Eigen::Vector2d vp = bi * v.segment<2>(2 * i) + bj * v.segment<2>(2 * j);
        const double vn = vp.dot(N);
        if (vn < 0.0) {
          const Eigen::Vector2d dvp = -vn * N + contact::coulomb(vp - vn * N, vn, c.friction);
          v.segment<2>(2 * i) += (wi * bi / k) * dvp;
          v.segment<2>(2 * j) += (wj * bj / k) * dvp;
        }
        ++contacts;
      }
    }
  }
  return contacts;
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

double edgeReach(const std::vector<CollisionEdge>& edges, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1) {
  // Each side of an edge's box is at most the edge's extent along it at the
  // end plus the travel of its two ends: |x_i − x_j|∞ + 2 max_k |x1_k − x0_k|∞.
  // (Both axes at once; with a coordinate not finite the reach may be any value.)
  using Point = Eigen::Map<const Eigen::Array2d>;
  const double* X = x1.data();
  Eigen::Array2d extent = Eigen::Array2d::Zero();
  for (const CollisionEdge& edge : edges) extent = extent.max((Point(X + 2 * edge.a) - Point(X + 2 * edge.b)).abs());
  const double travel = x1.size() > 0 ? (x1 - x0).cwiseAbs().maxCoeff() : 0.0;
  return extent.maxCoeff() + 2.0 * travel;
}

}  // namespace particles

// Collision edges (segments between two particles) against collider corners.
#include <algorithm>
#include <cmath>
#include <vector>

#include "contact_path.h"
#include "particles/collision.h"

namespace particles {

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

int resolveEdgeContacts(const std::vector<Collider>& colliders, const std::vector<CollisionEdge>& edges,
                        const StepStart& start, const Eigen::VectorXd& inverseMass, Eigen::VectorXd& x,
                        Eigen::VectorXd& v) {
  int contacts = 0;
  // Broad phase: a collider is tested against an edge only when their boxes
  // overlap (the edge's box spans its start and end, the collider's its corners).
  std::vector<Eigen::Vector2d> lo(colliders.size()), hi(colliders.size());
  std::vector<bool> cornered(colliders.size());
  for (std::size_t k = 0; k < colliders.size(); ++k)
    cornered[k] = colliders[k].shape != ColliderShape::HalfPlane && colliders[k].bounds(lo[k], hi[k]);
  for (const CollisionEdge& edge : edges) {
    const int i = edge.a, j = edge.b;
    const double wi = inverseMass[i], wj = inverseMass[j];
    if (wi + wj == 0.0) continue;
    const Eigen::Vector2d edgeLo = x.segment<2>(2 * i).cwiseMin(x.segment<2>(2 * j))
                                       .cwiseMin(start.x.segment<2>(2 * i)).cwiseMin(start.x.segment<2>(2 * j));
    const Eigen::Vector2d edgeHi = x.segment<2>(2 * i).cwiseMax(x.segment<2>(2 * j))
                                       .cwiseMax(start.x.segment<2>(2 * i)).cwiseMax(start.x.segment<2>(2 * j));
    for (std::size_t m = 0; m < colliders.size(); ++m) {
      // A half-plane has no corner: its particles keep edges out.
      if (!cornered[m] || (edgeLo.array() > hi[m].array()).any() || (edgeHi.array() < lo[m].array()).any()) continue;
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

}  // namespace particles

// The last guards of the contact pass (boundary_guard.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <optional>
#include <vector>

#include "contact_track.h"
#include "set_flags.h"
#include "boundary_guard.h"
#include "plane_geometry.h"
#include "particles/cancel.h"

namespace particles {

namespace {

// The collider the straight path a → b enters first (grown by r), if any.
std::optional<int> firstCollider(const std::vector<Collider>& colliders, const contact::ColliderBoxes& boxes,
                                 const Eigen::Vector2d& a, const Eigen::Vector2d& b, double r, double slop) {
  const Eigen::Vector2d lo = a.cwiseMin(b).array() - (r + slop), hi = a.cwiseMax(b).array() + (r + slop);
  std::optional<int> first;
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < static_cast<int>(colliders.size()); ++k) {
    if ((lo.array() > boxes.hi[k].array()).any() || (hi.array() < boxes.lo[k].array()).any()) continue;
    if (const std::optional<double> s = colliders[k].sweep(a, b, r, slop))
      if (*s < best) best = *s, first = k;
  }
  return first;
}

// How far the edge (xi, xj) is past the fixed point q (a corner, or a point
// of a capsule's core): its interior must stay at least the collider's radius
// beyond q on the side of the edge q was on at the step's start (si, sj).
// `ends`: q is over an end of the edge (b = 0 or 1), not inside it.
struct EdgePenetration {
  double depth = 0.0;           // > 0: the edge is at or past q
  double b = 0.0;               // q's place along the edge
  Eigen::Vector2d N{0.0, 0.0};  // unit normal of the edge pointing away from q's side
};

std::optional<EdgePenetration> edgePastPoint(double radius, const Eigen::Vector2d& q, bool ends,
                                             const Eigen::Vector2d& si, const Eigen::Vector2d& sj,
                                             const Eigen::Vector2d& xi, const Eigen::Vector2d& xj) {
  const Eigen::Vector2d e = xj - xi;
  const double length2 = e.squaredNorm();
  if (length2 == 0.0) return std::nullopt;
  // q over an end lies at b = 0 or 1 up to rounding.
  const double b = ends ? std::clamp((q - xi).dot(e) / length2, 0.0, 1.0) : (q - xi).dot(e) / length2;
  if (!ends && !(b > 0.0 && b < 1.0)) return std::nullopt;
  const double side0 = cross(sj - si, q - si);
  if (side0 == 0.0) return std::nullopt;
  const Eigen::Vector2d left = Eigen::Vector2d(-e.y(), e.x()) / std::sqrt(length2);
  const Eigen::Vector2d N = side0 > 0.0 ? -left : left;
  const double depth = radius + N.dot(q - xi);
  if (!(depth > 0.0)) return std::nullopt;
  return EdgePenetration{depth, b, N};
}

// The point of a capsule's core segment on the line through the edge point at
// b (0 or 1) perpendicular to the edge; none if the core does not reach that line.
std::optional<Eigen::Vector2d> coreOverEdgePoint(const Collider& c, const Eigen::Vector2d& xi,
                                                 const Eigen::Vector2d& xj, double b) {
  const Eigen::Vector2d e = xj - xi, p = xi + b * e, a = c.points[0], d = c.points[1] - c.points[0];
  const double along = e.dot(d);
  if (along == 0.0) return std::nullopt;  // the core is perpendicular to the edge: its corners decide
  const double u = e.dot(p - a) / along;  // e·(a + u d − p) = 0
  if (!(u >= 0.0 && u <= 1.0)) return std::nullopt;
  return a + u * d;
}

// Whether the segments p0 p1 and q0 q1 cross at a point inside both.
bool segmentsCross(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector2d& q0,
                   const Eigen::Vector2d& q1) {
  const Eigen::Vector2d p = p1 - p0, q = q1 - q0;
  return cross(p, q0 - p0) * cross(p, q1 - p0) < 0.0 && cross(q, p0 - q0) * cross(q, p1 - q0) < 0.0;
}

// Whether the edge (xi, xj) crosses a capsule's core, judged against the
// edge at the start (si, sj); the end that went round is returned. Either
// the core lies past the edge over one of its ends (on the far side of the
// side it started on), or the edge, clear of the core at the start, now
// cuts straight through it with both ends outside the capsule: one end went
// round a cap, and it is the end whose own straight path crosses the core
// (or, if neither does, the end nearer a cap).
std::optional<int> capsuleCrossedAtAnEnd(const Collider& c, const Eigen::Vector2d& si, const Eigen::Vector2d& sj,
                                         const Eigen::Vector2d& xi, const Eigen::Vector2d& xj) {
  for (const int end : {0, 1})
    if (const std::optional<Eigen::Vector2d> q = coreOverEdgePoint(c, xi, xj, end))
      if (edgePastPoint(c.radius, *q, true, si, sj, xi, xj)) return end;
  const Eigen::Vector2d& a = c.points[0];
  const Eigen::Vector2d& b = c.points[1];
  if (!segmentsCross(xi, xj, a, b) || segmentsCross(si, sj, a, b)) return std::nullopt;
  if (segmentsCross(si, xi, a, b)) return 0;
  if (segmentsCross(sj, xj, a, b)) return 1;
  const auto toCap = [&](const Eigen::Vector2d& p) { return std::min((p - a).norm(), (p - b).norm()); };
  return toCap(xi) <= toCap(xj) ? 0 : 1;
}

// How far the edge is past the deepest of the collider's corners (0: clear of all).
double deepestCorner(const Collider& c, const Eigen::Vector2d& si, const Eigen::Vector2d& sj,
                     const Eigen::Vector2d& xi, const Eigen::Vector2d& xj) {
  double deepest = 0.0;
  for (const Eigen::Vector2d& corner : c.points)
    if (const std::optional<EdgePenetration> hit = edgePastPoint(c.radius, corner, false, si, sj, xi, xj))
      deepest = std::max(deepest, hit->depth);
  return deepest;
}

// An end of the edge that went round a cap of a capsule to the far side of
// its core (while the other end stayed on the near side) cannot be pushed
// straight back: that would take it through the capsule. It is taken back
// along its own motion of the step, to the last place (found by bisection) at
// which the edge still passes the core on its starting side, and its
// velocity's approach to the core is removed.
int holdEdgeEndOffCapsule(const std::vector<Collider>& colliders, const Collider& c, const StepStart& start,
                          const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius, const CollisionEdge& edge,
                          Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd& lastFree) {
  const int ends[2] = {edge.a, edge.b};
  const Eigen::Vector2d si = start.x.segment<2>(2 * edge.a), sj = start.x.segment<2>(2 * edge.b);
  const std::optional<int> crossed = capsuleCrossedAtAnEnd(c, si, sj, x.segment<2>(2 * edge.a), x.segment<2>(2 * edge.b));
  if (!crossed) return 0;
  const int moved = ends[*crossed];
  if (inverseMass[moved] == 0.0) return 0;
  const Eigen::Vector2d from = start.x.segment<2>(2 * moved), to = x.segment<2>(2 * moved);
  // Blocked: the edge crosses the core over an end, or is deeper past a
  // corner than it was with the end at its start (the corners' push deals
  // with that much), or the end is inside a collider.
  double cornerDepth = std::numeric_limits<double>::infinity();
  const auto placed = [&](double s) {
    x.segment<2>(2 * moved) = from + s * (to - from);
    for (const Collider& other : colliders)
      if (other.distance(x.segment<2>(2 * moved)).distance < radius[moved]) return true;
    const Eigen::Vector2d xi = x.segment<2>(2 * edge.a), xj = x.segment<2>(2 * edge.b);
    if (capsuleCrossedAtAnEnd(c, si, sj, xi, xj)) return true;
    return deepestCorner(c, si, sj, xi, xj) > cornerDepth;
  };
  if (placed(0.0)) {  // crossed even from the start: the push of the corners is all there is
    placed(1.0);
    return 0;
  }
  cornerDepth = deepestCorner(c, si, sj, x.segment<2>(2 * edge.a), x.segment<2>(2 * edge.b));
  double clear = 0.0, crossing = 1.0;
  for (int k = 0; k < 30; ++k) {
    const double s = 0.5 * (clear + crossing);
    (placed(s) ? crossing : clear) = s;
  }
  placed(clear);
  lastFree.segment<2>(2 * moved) = x.segment<2>(2 * moved);  // outside every collider
  // The approach to the core along the normal from its nearest point is removed.
  const SurfaceDistance d = c.distance(x.segment<2>(2 * moved));
  const double vn = v.segment<2>(2 * moved).dot(d.normal);
  if (vn < 0.0) v.segment<2>(2 * moved) -= vn * d.normal;
  return 1;
}

}  // namespace

int holdEdgeEndsOffCapsules(const std::vector<Collider>& colliders, const std::vector<CollisionEdge>& edges,
                            const StepStart& start, const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                            Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd& lastFree,
                            const std::vector<int>& candidates) {
  int held = 0;
  for (const int k : candidates) {
    const CollisionEdge& edge = edges[k];
    if (inverseMass[edge.a] + inverseMass[edge.b] == 0.0) continue;
    for (const Collider& c : colliders)
      if (c.shape == ColliderShape::Capsule)
        held += holdEdgeEndOffCapsule(colliders, c, start, inverseMass, radius, edge, x, v, lastFree);
  }
  return held;
}

int pushOutOfColliders(const std::vector<Collider>& colliders, const std::vector<int>& particles,
                       const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                       const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v,
                       Eigen::VectorXd& lastFree, int& capped) {
  const contact::ColliderBoxes boxes(colliders);
  int pushed = 0;
  CancelPoll cancel(64);
  for (const int i : particles) {
    if (cancel.poll()) break;
    if (inverseMass[i] == 0.0) continue;
    const double r = radius[i];
    Eigen::Vector2d x1 = x.segment<2>(2 * i), v1 = v.segment<2>(2 * i);
    Eigen::Vector2d from = lastFree.segment<2>(2 * i);
    if (from == x1) continue;  // not moved since it was known to be outside
    int pass = 0;
    for (; pass < settings.maxImpacts && !cancel.poll(); ++pass) {
      const std::optional<int> hit = firstCollider(colliders, boxes, from, x1, r, settings.slop);
      if (!hit) break;
      const Collider& c = colliders[*hit];
      // The face entered on the way from the last free position: back onto
      // it along its normal, the approach removed, Coulomb friction applied.
      Eigen::Vector2d normal;
      const double s = *c.sweep(from, x1, r, settings.slop);
      const Eigen::Vector2d p = contact::ontoSurface(c, from + s * (x1 - from), r, &normal);
      if (r == 0.0) normal = c.entryNormal(p, x1 - from, settings.slop);  // a corner: the face the path went into
      x1 += std::max(0.0, normal.dot(p - x1)) * normal;
      const double vn = v1.dot(normal);
      if (vn < 0.0) v1 += -vn * normal + contact::coulomb(v1 - vn * normal, vn, c.friction);
      from = p;
      ++pushed;
    }
    if (pass == settings.maxImpacts && firstCollider(colliders, boxes, from, x1, r, settings.slop)) {
      x1 = from;  // out of passes: back to the last point known outside
      ++capped;
    }
    x.segment<2>(2 * i) = x1;
    v.segment<2>(2 * i) = v1;
    lastFree.segment<2>(2 * i) = x1;
  }
  return pushed;
}

namespace {

constexpr int kHoldPasses = 16;

// Whether the interior of the edge, its ends moved in straight lines from
// (si, sj) to (si + s di, sj + s dj) for s in [0, u], passes over the point q:
// the side of the edge q is on, f(s) = e(s) × (q − x_i(s)), a quadratic in s,
// is zero with q over the edge's interior (0 < b < 1).
bool edgeSweepsOver(const Eigen::Vector2d& q, const Eigen::Vector2d& si, const Eigen::Vector2d& sj,
                    const Eigen::Vector2d& di, const Eigen::Vector2d& dj, double u) {
  const Eigen::Vector2d e0 = sj - si, de = dj - di, r0 = q - si;
  const double c0 = cross(e0, r0), c1 = cross(de, r0) - cross(e0, di), c2 = -cross(de, di);
  if (c0 == 0.0) return false;  // q on the edge's line at the start: on no side of it
  const auto overInterior = [&](double s) {
    if (!(s > 0.0 && s <= u)) return false;
    const Eigen::Vector2d e = e0 + s * de, r = r0 - s * di;
    const double length2 = e.squaredNorm(), b = r.dot(e);
    return length2 > 0.0 && b > 0.0 && b < length2;
  };
  const double scale = std::abs(c0) + std::abs(c1) + std::abs(c2);
  if (std::abs(c2) <= 1e-12 * scale) return c1 != 0.0 && overInterior(-c0 / c1);
  const double discriminant = c1 * c1 - 4.0 * c2 * c0;
  if (discriminant < 0.0) return false;
  // The stable pair of roots: q = −(c1 + sign(c1) √D) / 2, s = q / c2 and c0 / q.
  const double root = -0.5 * (c1 + std::copysign(std::sqrt(discriminant), c1));
  return overInterior(root / c2) || (root != 0.0 && overInterior(c0 / root));
}

// Whether `point` lies over the interior of the edge (p, q), nearer than `keep` to its line.
bool overInteriorWithin(const Eigen::Vector2d& point, const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                        double keep) {
  const Eigen::Vector2d e = q - p, r = point - p;
  const double length2 = e.squaredNorm(), b = r.dot(e);
  return length2 > 0.0 && b > 0.0 && b < length2 && std::abs(cross(e, r)) < keep * std::sqrt(length2);
}

// Whether the edge, its ends taken a fraction u of their step (from `from`
// to `to`), has crossed the core of a capsule or disc: its interior swept
// over a disc's centre or an end of a capsule's core, or it cuts through a
// capsule's core at u and did not at the start (an end of the edge moved
// across it), or (`keep` > 0) it has one of those points over its interior
// nearer than `keep` to it.
bool coreCrossed(const Collider& c, const Eigen::Vector2d from[2], const Eigen::Vector2d to[2], double u,
                 double keep = 0.0) {
  const Eigen::Vector2d p = from[0] + u * (to[0] - from[0]), q = from[1] + u * (to[1] - from[1]);
  for (const Eigen::Vector2d& point : c.points)
    if (edgeSweepsOver(point, from[0], from[1], to[0] - from[0], to[1] - from[1], u) ||
        overInteriorWithin(point, p, q, keep))
      return true;
  if (c.shape == ColliderShape::Disc) return false;
  const Eigen::Vector2d &a = c.points[0], &b = c.points[1];
  return segmentsCross(p, q, a, b) && !segmentsCross(from[0], from[1], a, b);
}

bool hasCore(const Collider& c) { return c.shape == ColliderShape::Capsule || c.shape == ColliderShape::Disc; }

// The last guard of a step against an edge cutting through the core of a
// capsule or disc (the contacts after the edge passes, the push out of the
// colliders above all, may have moved an end across): an edge that crossed
// the core over the step has both ends taken back along their motion of the
// step to the last place (found by bisection) at which it has not and
// neither end is inside a collider, and their approach to the core is
// removed. A disc's centre and the ends of a capsule's core are kept off
// the held edge's line by half their distance from the edge at the start (at
// most half the radius, at least a thousandth of it): an edge left with such
// a point on its line would start the next step on no side of it.
int holdEdgeOffCore(const std::vector<Collider>& colliders, const Collider& c, const StepStart& start,
                    const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius, const CollisionEdge& edge,
                    Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd& lastFree) {
  const int ends[2] = {edge.a, edge.b};
  Eigen::Vector2d from[2], to[2];
  for (int k = 0; k < 2; ++k) {
    from[k] = start.x.segment<2>(2 * ends[k]);
    to[k] = inverseMass[ends[k]] == 0.0 ? from[k] : Eigen::Vector2d(x.segment<2>(2 * ends[k]));
  }
  if (!coreCrossed(c, from, to, 1.0)) return 0;
  double keep = c.radius;
  for (const Eigen::Vector2d& point : c.points)
    keep = std::min(keep, (point - nearestOnSegment(point, from[0], from[1])).norm());
  // Never less than a thousandth of the radius: halved step after step, the
  // distance would shrink until a motion below rounding put the point on the
  // other side.
  keep = std::max(0.5 * keep, 1e-3 * c.radius);
  const auto placed = [&](double s) {
    bool inside = false;
    for (int k = 0; k < 2; ++k) {
      if (inverseMass[ends[k]] == 0.0) continue;
      const Eigen::Vector2d p = from[k] + s * (to[k] - from[k]);
      x.segment<2>(2 * ends[k]) = p;
      for (const Collider& other : colliders) inside = inside || other.distance(p).distance < radius[ends[k]];
    }
    return coreCrossed(c, from, to, s, keep) || (s > 0.0 && inside);
  };
  double clear = 0.0, crossing = 1.0;
  for (int k = 0; k < 30; ++k) {
    const double s = 0.5 * (clear + crossing);
    (placed(s) ? crossing : clear) = s;
  }
  placed(clear);
  for (const int end : ends) {
    if (inverseMass[end] == 0.0) continue;
    lastFree.segment<2>(2 * end) = x.segment<2>(2 * end);
    const SurfaceDistance d = c.distance(x.segment<2>(2 * end));
    const double vn = v.segment<2>(2 * end).dot(d.normal);
    if (vn < 0.0) v.segment<2>(2 * end) -= vn * d.normal;
  }
  return 1;
}

}  // namespace

int holdEdgesOffCores(const std::vector<Collider>& colliders, const std::vector<CollisionEdge>& edges,
                      const StepStart& start, const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                      Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd& lastFree,
                      const std::vector<int>& candidates) {
  if (std::none_of(colliders.begin(), colliders.end(), hasCore)) return 0;
  // An end held back for one edge may leave another edge at it crossing:
  // passes until none is held.
  int held = 0;
  for (int pass = 0; pass < kHoldPasses && !cancelRequested(); ++pass) {
    int heldNow = 0;
    for (const int k : candidates) {
      const CollisionEdge& edge = edges[k];
      if (inverseMass[edge.a] + inverseMass[edge.b] == 0.0) continue;
      for (const Collider& c : colliders)
        if (hasCore(c))
          heldNow += holdEdgeOffCore(colliders, c, start, inverseMass, radius, edge, x, v, lastFree);
    }
    held += heldNow;
    if (heldNow == 0) break;
  }
  return held;
}

}  // namespace particles

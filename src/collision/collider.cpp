#include "particles/collider.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "particles/check.h"
#include "contact_path.h"
#include "particles/constants.h"
#include "plane_geometry.h"

namespace particles {

const std::vector<ColliderKind>& colliderKinds() {
  static const std::vector<ColliderKind> kinds = {{ColliderShape::HalfPlane, "halfPlane"},
                                                  {ColliderShape::Box, "box"},
                                                  {ColliderShape::Polygon, "polygon"},
                                                  {ColliderShape::Capsule, "capsule"},
                                                  {ColliderShape::Disc, "disc"}};
  return kinds;
}

const char* colliderName(ColliderShape shape) {
  for (const ColliderKind& kind : colliderKinds())
    if (kind.shape == shape) return kind.name;
  return "collider";
}

namespace {

// Outward normal of the counter-clockwise edge a → b (its right-hand side).
Eigen::Vector2d outwardNormal(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  return Eigen::Vector2d(e.y(), -e.x()) / e.norm();
}

// The edges whose offset lines bound the grown shape: a polygon's closed loop;
// a capsule's segment taken both ways (its two sides); none for a disc.
template <class Visit>
void forEachEdge(const std::vector<Eigen::Vector2d>& p, Visit&& visit) {
  const std::size_t n = p.size();
  if (n == 2) {
    visit(p[0], p[1]);
    visit(p[1], p[0]);
  } else if (n >= 3) {
    for (std::size_t k = 0; k < n; ++k) visit(p[k], p[(k + 1) % n]);
  }
}

// Distances within this of p are round-off of p's coordinates.
double roundOffAt(const Eigen::Vector2d& p) { return 1e-12 * (1.0 + p.cwiseAbs().maxCoeff()); }

}  // namespace

Collider Collider::halfPlane(const Eigen::Vector2d& point, const Eigen::Vector2d& n) {
  Collider c;
  c.shape = ColliderShape::HalfPlane;
  c.points = {point};
  // n·n overflows for components near 1e308 and underflows near 1e-200,
  // though the direction is plain: those are first divided by their largest
  // magnitude. A zero or non-finite n is kept as given, for validate() to report.
  const double squared = n.squaredNorm(), largest = n.cwiseAbs().maxCoeff();
  if (squared > 0.0 && std::isfinite(squared)) c.normal = n.normalized();
  else c.normal = n.allFinite() && largest > 0.0 ? Eigen::Vector2d((n / largest).normalized()) : n;
  return c;
}

Collider Collider::box(const Eigen::Vector2d& min, const Eigen::Vector2d& max) {
  Collider c;
  c.shape = ColliderShape::Box;
  c.points = {min, {max.x(), min.y()}, max, {min.x(), max.y()}};
  return c;
}

Collider Collider::polygon(const std::vector<Eigen::Vector2d>& vertices) {
  Collider c;
  c.shape = ColliderShape::Polygon;
  c.points = vertices;
  return c;
}

Collider Collider::capsule(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius) {
  Collider c;
  c.shape = ColliderShape::Capsule;
  c.points = {a, b};
  c.radius = radius;
  return c;
}

Collider Collider::disc(const Eigen::Vector2d& centre, double radius) {
  Collider c;
  c.shape = ColliderShape::Disc;
  c.points = {centre};
  c.radius = radius;
  return c;
}

void Collider::validate() const {
  const std::string kind = colliderName(shape);
  for (const Eigen::Vector2d& p : points)
    if (!p.allFinite()) throw std::invalid_argument(kind + " points must be finite, got (" + formatValue(p.x()) +
                                                    ", " + formatValue(p.y()) + ")");
  requireInRange("collider restitution", restitution, 0.0, 1.0);
  requireNonNegative("collider friction", friction);
  switch (shape) {
    case ColliderShape::HalfPlane:
      if (points.size() != 1 || !normal.allFinite() || std::abs(normal.norm() - 1.0) > 1e-9)
        throw std::invalid_argument("halfPlane normal must be a non-zero finite vector, got (" +
                                    formatValue(normal.x()) + ", " + formatValue(normal.y()) + ")");
      break;
    case ColliderShape::Box:
      if (points.size() != 4 || !(points[2].x() > points[0].x()) || !(points[2].y() > points[0].y()))
        throw std::invalid_argument("box max must exceed min on both axes");
      break;
    case ColliderShape::Capsule:
      requirePositive("capsule radius", radius);
      if (points.size() != 2 || (points[1] - points[0]).norm() <= 1e-12 * (1.0 + points[0].norm()))
        throw std::invalid_argument("capsule segment must have non-zero length");
      break;
    case ColliderShape::Disc:
      requirePositive("disc radius", radius);
      break;
    case ColliderShape::Polygon: {
      const std::size_t n = points.size();
      if (n < 3)
        throw std::invalid_argument("polygon needs at least 3 vertices, got " + std::to_string(n));
      // Convex and counter-clockwise: every turn is to the left, and the
      // edges wind round once (the angles of the turns sum to 2π).
      double winding = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        const Eigen::Vector2d e1 = points[(k + 1) % n] - points[k], e2 = points[(k + 2) % n] - points[(k + 1) % n];
        if (e1.norm() == 0.0)
          throw std::invalid_argument("polygon vertex " + std::to_string((k + 1) % n) + " repeats vertex " +
                                      std::to_string(k));
        if (!(cross(e1, e2) > 0.0))
          throw std::invalid_argument("polygon must be convex with vertices counter-clockwise, but it turns right "
                                      "or goes straight at vertex " + std::to_string((k + 1) % n));
        winding += std::atan2(cross(e1, e2), e1.dot(e2));
      }
      if (std::abs(winding - 2.0 * kPi) > 1e-6)
        throw std::invalid_argument("polygon must be convex: its edges wind round " +
                                    formatValue(winding / (2.0 * kPi)) + " times");
      break;
    }
  }
}

SurfaceDistance Collider::distance(const Eigen::Vector2d& p) const {
  if (shape == ColliderShape::HalfPlane) return {normal.dot(p - points[0]), normal};
  if (points.size() == 1) {
    const Eigen::Vector2d d = p - points[0];
    const double r = d.norm();
    return {r - radius, r > 0.0 ? Eigen::Vector2d(d / r) : Eigen::Vector2d(0.0, 1.0)};
  }
  // Nearest point q of the hull's boundary, over its edges.
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d nearest = points[0], edgeNormal(0.0, 1.0);
  bool inside = points.size() >= 3;
  forEachEdge(points, [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d q = nearestOnSegment(p, a, b);
    const double d2 = (p - q).squaredNorm();
    if (cross(b - a, p - a) < 0.0) inside = false;  // right of a counter-clockwise edge
    if (d2 < best) {
      best = d2;
      nearest = q;
      edgeNormal = outwardNormal(a, b);
    }
  });
  const double d = std::sqrt(best);
  // Inside a convex polygon the nearest boundary point lies straight out along
  // its edge's normal; on (or within round-off of) the boundary the direction
  // p − q is noise, and on a capsule's axis either side will do.
  if (inside) return {-d - radius, edgeNormal};
  return {d - radius, d > roundOffAt(p) ? Eigen::Vector2d((p - nearest) / d) : edgeNormal};
}

Eigen::Vector2d Collider::entryNormal(const Eigen::Vector2d& p, const Eigen::Vector2d& heading, double slop) const {
  const SurfaceDistance surface = distance(p);
  if (points.size() < 3 || radius > 0.0) return surface.normal;
  // Among the faces passing within slop of p: the one the heading goes into
  // most, unless it leaves one of them (near a corner the shape is the
  // intersection of its faces' half-planes, so such a path stays outside).
  const double near = std::max(slop, roundOffAt(p)), leaving = std::max(slop, 1e-12 * heading.norm());
  Eigen::Vector2d into = surface.normal, out = surface.normal;
  double least = 0.0, most = 0.0;
  bool found = false;
  forEachEdge(points, [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    if ((p - nearestOnSegment(p, a, b)).norm() > near) return;
    const Eigen::Vector2d n = outwardNormal(a, b);
    const double along = n.dot(heading);
    if (!found || along < least) {
      least = along;
      into = n;
    }
    if (!found || along > most) {
      most = along;
      out = n;
    }
    found = true;
  });
  return found && most > leaving ? out : into;
}

std::optional<double> Collider::sweep(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double margin,
                                      double slop) const {
  const SurfaceDistance start = distance(a);
  const double startGap = start.distance - margin;
  const Eigen::Vector2d d = b - a;
  if (startGap <= slop) {
    // At a corner of a box or polygon the face the path heads into decides,
    // and a path that leaves either face misses.
    const Eigen::Vector2d n = margin == 0.0 ? entryNormal(a, d, slop) : start.normal;
    if (n.dot(d) < -slop || distance(b).distance - margin < -slop) return 0.0;
    return std::nullopt;
  }
  if (shape == ColliderShape::HalfPlane) {
    const double endGap = distance(b).distance - margin;
    if (endGap >= 0.0) return std::nullopt;
    return startGap / (startGap - endGap);
  }
  const double R = radius + margin;
  std::optional<double> first;
  auto keep = [&](double s) {
    if (!first || s < *first) first = s;
  };
  // Entering through an edge's offset line n·(x − p_k) = R within the edge's extent.
  forEachEdge(points, [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    const Eigen::Vector2d n = outwardNormal(p, q), e = q - p;
    const double approach = n.dot(d);
    if (!(approach < 0.0)) return;
    const double gap = n.dot(a - p) - R;
    if (gap < 0.0) return;  // behind this offset line: entry is through another piece
    const double s = gap / -approach;
    if (s > 1.0) return;
    // Within the edge's extent, its ends included to round-off: a path along
    // the line of the next face enters at the corner.
    const double t = (a + s * d - p).dot(e) / e.squaredNorm();
    if (t >= -1e-12 && t <= 1.0 + 1e-12) keep(s);
  });
  // Entering a vertex's circle of radius R (the rounded corners and ends).
  if (R > 0.0)
    for (const Eigen::Vector2d& c : points)
      if (const std::optional<double> s = contact::enterCircle(a, d, c, R)) keep(*s);
  return first;
}

bool Collider::bounds(Eigen::Vector2d& min, Eigen::Vector2d& max) const {
  if (shape == ColliderShape::HalfPlane) return false;
  min = max = points[0];
  for (const Eigen::Vector2d& p : points) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  min.array() -= radius;
  max.array() += radius;
  return true;
}

}  // namespace particles

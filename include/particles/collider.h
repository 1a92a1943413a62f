#pragma once
// Colliders: static convex shapes that particles (and collision edges) cannot
// enter. Every kind is one convex set described by a few points and a
// rounding radius r (the set of points within r of the convex hull of the
// points), so one distance and one sweep serve them all:
//   halfPlane  {x : n·(x − p) ≤ 0}, p = points[0], n the outward unit normal
//   box        axis-aligned rectangle, points = its 4 corners counter-clockwise, r = 0
//   polygon    convex polygon, ≥ 3 vertices counter-clockwise, r = 0
//   capsule    segment points[0]–points[1] thickened by r > 0 (a rounded slab)
//   disc       points[0] with radius r > 0 (a nail, a peg)
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace particles {

enum class ColliderShape { HalfPlane, Box, Polygon, Capsule, Disc };

// The names used by scene files and tools, in one table.
struct ColliderKind {
  ColliderShape shape;
  const char* name;
};
const std::vector<ColliderKind>& colliderKinds();
const char* colliderName(ColliderShape shape);

// Signed distance to a collider's surface (negative inside) and the outward
// unit normal of the surface point nearest to the query point.
struct SurfaceDistance {
  double distance;
  Eigen::Vector2d normal;
};

struct Collider {
  ColliderShape shape = ColliderShape::Box;
  std::vector<Eigen::Vector2d> points;  // see the table above, world units
  Eigen::Vector2d normal{0.0, 1.0};     // half-plane only: outward unit normal
  double radius = 0.0;                  // rounding radius r, world units
  double restitution = 0.5;             // e in [0, 1]: normal speed after / before impact
  double friction = 0.0;                // Coulomb μ ≥ 0: |tangential impulse| ≤ μ · normal impulse

  static Collider halfPlane(const Eigen::Vector2d& point, const Eigen::Vector2d& normal);
  static Collider box(const Eigen::Vector2d& min, const Eigen::Vector2d& max);
  static Collider polygon(const std::vector<Eigen::Vector2d>& vertices);
  static Collider capsule(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double radius);
  static Collider disc(const Eigen::Vector2d& centre, double radius);

  // Throws std::invalid_argument naming the bad field: non-finite points, a
  // zero-length capsule, a polygon that is not convex and counter-clockwise,
  // a box with max not above and right of min, e outside [0, 1], μ < 0.
  void validate() const;

  // Distance from p to the surface of the collider grown by `margin` (a
  // particle's radius) is distance(p).distance − margin.
  SurfaceDistance distance(const Eigen::Vector2d& p) const;
  // The outward normal of the face that a path heading along `heading`
  // (a displacement) enters at the surface point p: distance(p).normal,
  // except at a corner of a box or polygon (p within slop, or round-off, of
  // two faces), where it is the face the heading goes into most, the least
  // n·heading (a particle sliding along a floor into a wall that stands on it
  // meets the wall's face, not the bottom face of the wall it is level with).
  // A heading that leaves one of the corner's faces (n·heading > slop) does
  // not enter, since near the corner the shape is the intersection of the
  // faces' half-planes: that face's normal is returned, and sweep() finds no
  // hit there.
  Eigen::Vector2d entryNormal(const Eigen::Vector2d& p, const Eigen::Vector2d& heading, double slop = 0.0) const;

  // First fraction s ∈ [0, 1] of the straight path a → b at which the path
  // reaches distance `margin` from the surface, i.e. enters the collider grown
  // by margin. A path that starts within slop of the grown surface hits at
  // s = 0 if it heads inwards by more than slop or ends deeper than slop
  // inside; otherwise it is leaving and does not hit.
  std::optional<double> sweep(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double margin,
                              double slop) const;

  // The corners of the axis-aligned bounding box; false for a half-plane.
  bool bounds(Eigen::Vector2d& min, Eigen::Vector2d& max) const;
};

}  // namespace particles

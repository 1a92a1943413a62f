// Small pieces of plane geometry shared by the forces and the contacts.
#pragma once

#include <algorithm>

#include <Eigen/Core>

namespace particles {

// The z component of the cross product of two plane vectors: positive when
// b turns to the left of a.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// The point of the segment a → b nearest to p.
inline Eigen::Vector2d nearestOnSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  return a + std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0) * e;
}

}  // namespace particles

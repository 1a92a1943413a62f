#pragma once
// A particle that starts inside a collider deeper than rounding has no
// shortest way out that adds no energy (at a disc's centre, none at all), so
// no scene may start so: the scene-file reader refuses such a file at the
// particle's JSON path, and the scene table refuses built-in parameters that
// would build one (so every export reads back). One definition of "inside"
// for both:
//   depth = r_i − d_c(x_i) > startingOverlapTolerance(x_i),
// d_c the signed distance to collider c's surface and r_i the particle's
// radius (0 for a point).
//
// Cost: a broad phase (a uniform grid over the particles, about one particle
// a cell; each collider visits the cells its box meets, grown by the largest
// radius) leaves only the particles inside a collider's box for the exact
// distance, so the check is linear in the particles plus the colliders'
// vertices (and the cells their boxes cover), with each particle inside a
// collider's box paying that collider's vertices once. Half-planes have no box
// and meet every particle (one dot product each).
#include <cstddef>
#include <optional>

#include <Eigen/Core>

#include "particles/particle_system.h"

namespace scenes {

// How deep inside a collider a particle at x may start: rounding of its
// coordinates, 1e-6 of its distance from the origin, at least 1e-6.
double startingOverlapTolerance(const Eigen::Vector2d& x);

struct StartingOverlap {
  int particle;
  std::size_t collider;  // index into the system's colliders()
  double depth;          // r − d > tolerance, world units
};

// The overlap of the lowest particle index (then the lowest collider index),
// or none. With `cancellable` (the reader of a user's file), throws
// particles::Cancelled when the cancel flag goes up (particles/cancel.h).
std::optional<StartingOverlap> firstStartingOverlap(const particles::ParticleSystem& system,
                                                    bool cancellable = false);

}  // namespace scenes

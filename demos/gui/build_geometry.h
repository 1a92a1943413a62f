#pragma once
// Where the objects of a scene being built are on screen, for picking them
// with the mouse and outlining the one selected: every force and constraint
// by its own sketch (Force::sketch, Constraint::sketch), a collider by its
// points and radius, a particle by its position. No OpenGL here.
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "particles/particle_system.h"
#include "particles/phase.h"
#include "scene_document.h"

namespace demo {

// The outline of one object of the document, as drawn in the system built
// from it (same order of objects; the document's walls come first among the
// system's colliders). `reach` is the length drawn of what has none (a
// half-plane's surface). Empty for what has no place (gravity, drag, the scene).
particles::Sketch outlineOf(const Json& document, const particles::ParticleSystem& system, const ObjectRef& ref,
                            double reach);

// Distance from p to the nearest line or circle of a sketch (infinite when empty).
double distanceTo(const particles::Sketch& sketch, const Eigen::Vector2d& p);

// The object under p, within `radius` (world units): the nearest particle if
// any is that near, else the nearest force, constraint, collision edge or
// collider outline; a press inside a collider picks it too.
std::optional<ObjectRef> pickObject(const Json& document, const particles::ParticleSystem& system,
                                    const Eigen::Vector2d& p, double radius);

// The nearest particle to p within radius, if any.
std::optional<int> nearestParticle(const particles::ParticleSystem& system, const Eigen::Vector2d& p, double radius);

// The convex hull of points, counter-clockwise, without repeated or collinear
// points (Andrew's monotone chain): the polygon tool's vertices.
std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> points);

}  // namespace demo

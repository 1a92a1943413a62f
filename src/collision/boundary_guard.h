#pragma once
// The last stage of the contact pass: guards that hold the colliders as a hard
// boundary whatever the solve before them left (its caps reached, a move
// along a constraint into a collider). Each repairs only what is wrong, so a
// solved step passes through them unchanged.
#include <vector>

#include <Eigen/Core>

#include "contact_types.h"
#include "particles/collider.h"
#include "particles/collision.h"

namespace particles {

// Particles that end inside a collider: the path lastFree → x (lastFree known
// outside every collider) finds the face entered; the particle is put back on
// it and its approach (with Coulomb friction) removed, until no collider is
// entered. Updates lastFree; returns the pushes made, and counts in `capped`
// the particles still entering a collider after maxImpacts passes (put back
// at their last point known outside).
int pushOutOfColliders(const std::vector<Collider>& colliders, const std::vector<int>& particles,
                       const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                       const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v,
                       Eigen::VectorXd& lastFree, int& capped);

// An end of a collision edge that went round a cap of a capsule to the far
// side of its core (while the other end stayed on the near side) cannot be
// pushed straight back: that would take it through the capsule. It is taken
// back along its own motion of the step, to the last place (bisection) at
// which the edge still passes the core on its starting side, outside every
// collider (by the particle's radius), and lastFree records it there; its
// approach to the core is removed. candidates: indices into `edges`.
// Returns how many ends were held.
int holdEdgeEndsOffCapsules(const std::vector<Collider>& colliders, const std::vector<CollisionEdge>& edges,
                            const StepStart& start, const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                            Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd& lastFree,
                            const std::vector<int>& candidates);

// The last guard against an edge cutting through the core of a capsule or a
// disc: each candidate edge (indices into `edges`) that crosses a capsule's
// core at x but not at the step's start, or whose interior passed over a
// disc's centre (its ends moved in straight lines from the start to x), is
// taken back along the step of its ends to where it has not (passes until
// none is held, at most 16); returns how many times an edge was held.
int holdEdgesOffCores(const std::vector<Collider>& colliders, const std::vector<CollisionEdge>& edges,
                      const StepStart& start, const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                      Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd& lastFree,
                      const std::vector<int>& candidates);

}  // namespace particles

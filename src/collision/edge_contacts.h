#pragma once
// Collision edges (segments between particles, e.g. a cloth's springs)
// against the corners and cores of colliders.
#include <vector>

#include <Eigen/Core>

#include "contact_types.h"
#include "particles/collider.h"
#include "particles/collision.h"

namespace particles {

// Edges against the corners of colliders (the vertices of boxes, polygons and
// capsules, and the centres of discs, grown by the collider's radius): a
// corner on one side of an edge at the step's start may not be on the other
// side, or nearer than its radius, at the end. The edge is pushed clear with
// the weights of the point of the edge facing the corner, its approach
// removed and Coulomb friction applied. A capsule's core may also not cross
// the edge over one of its ends (an end gone round a cap to the far side):
// that end is taken back along its step to where the edge passes the core on
// its starting side, outside every collider (by the particle's radius), and
// lastFree records it there. Returns the contacts.
// `candidates` (null: every edge is tested) lists the indices into `edges` to
// test, ascending: those with an end marked by markNearColliders (EdgeIncidence).
int resolveEdgeContacts(const std::vector<Collider>& colliders, const std::vector<CollisionEdge>& edges,
                        const StepStart& start, const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                        Eigen::VectorXd& x, Eigen::VectorXd& v, Eigen::VectorXd& lastFree,
                        const std::vector<int>* candidates = nullptr);

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

#pragma once
// The narrow phase of the contact pass: the contacts (contact.h) at the
// step's end, one function per kind, after the impacts stage has bounced
// what bounces. Each appends to `out`.
//
// - A particle (point or disc of radius r) against a collider: the path from
//   its reference (the step's start, or its last impact) to its end is swept
//   against the collider grown by r; the face it entered (at a corner of a
//   box or polygon, the face the path heads into most) gives the contact
//   plane; a path that enters nothing but ends within the slop of the
//   surface touches at its end.
// - Two discs: touching or overlapping at the end, or their relative path
//   entered the circle of their summed radii during the step (the normal is
//   then that of the entry, so discs that passed through each other are
//   pushed back the way they came).
// - A collision edge against a corner (a vertex of a box, polygon or
//   capsule, a disc's centre; each grown by the collider's radius): the
//   corner lies over the edge's interior and within reach of it at the end,
//   or past it, measured from the side of the edge it was on at the step's
//   start.
//
// A contact new this step that approaches bounces (Contact::bounce, the
// solver's target for its normal): e × the impact speed, recovered from the
// end speed and the depth reached (v_impact² = v_n² + 2 a_n d), when that is
// above ContactSettings::restitutionThreshold.
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "contact.h"
#include "contact_solver.h"
#include "contact_types.h"
#include "impacts.h"
#include "particles/collider.h"
#include "particles/collision.h"

namespace particles {

// What every kind reads.
struct NarrowInput {
  const std::vector<Collider>& colliders;
  const StepStart& start;
  const References& refs;
  const Eigen::VectorXd& inverseMass;
  const Eigen::VectorXd& radius;
  const ContactSettings& settings;
  const ContactSolver& last;  // a contact it solved last time (ContactSolver::persists) is not new: no bounce
};

void colliderContacts(const NarrowInput& in, const std::vector<int>& particles, const Eigen::VectorXd& x,
                      const Eigen::VectorXd& v, std::vector<Contact>& out);

// pairs: indices into `discs`.
void discPairContacts(const NarrowInput& in, const std::vector<int>& discs,
                      const std::vector<std::pair<int, int>>& pairs, const Eigen::VectorXd& x,
                      const Eigen::VectorXd& v, std::vector<Contact>& out);

// candidates: indices into `edges`.
void edgeCornerContacts(const NarrowInput& in, const std::vector<CollisionEdge>& edges,
                        const std::vector<int>& candidates, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                        std::vector<Contact>& out);

// Contacts the solve ran into: particles (of `particles`) whose path from
// their reference to the solved position x enters a collider they had no
// contact with (a particle sliding along a floor into a wall that stands on
// it: its free path went down, not into the wall), and disc pairs (of
// `pairs`) left overlapping with no contact. Their bounces are judged on the
// velocities `before` the solve. Appends to `found`; returns how many.
int missedContacts(const NarrowInput& in, const std::vector<int>& particles, const std::vector<int>& discs,
                   const std::vector<std::pair<int, int>>& pairs, const Eigen::VectorXd& x,
                   const Eigen::VectorXd& before, std::vector<Contact>& found);

}  // namespace particles

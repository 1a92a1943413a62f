#pragma once
// Particles against colliders: the continuous sweep of each particle's path
// and the resting pass for particles pushed into a collider afterwards.
#include <vector>

#include <Eigen/Core>

#include "contact_types.h"
#include "particles/collider.h"
#include "particles/collision.h"

namespace particles {

// Particles (discs of radius[i], 0 for a point) against colliders: each
// particle's path over the step is swept against every collider; at the
// first impact the normal velocity becomes −e times the impact velocity and
// the tangential impulse is Coulomb's (at most μ times the normal impulse);
// the rest of the path is swept again from there, so touching colliders act
// as one closed boundary. Pinned particles (inverse mass 0) are never moved.
// `only` (null: all) lists the particles to resolve, the others are left
// alone. `lastFree` (2n) receives each resolved particle's end position (known
// to be outside every collider), from which pushOutOfColliders sweeps later.
// Returns the contacts and the particles that ran out of maxImpacts.
ContactCount resolveColliderContacts(const std::vector<Collider>& colliders, const StepStart& start,
                            const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                            const ContactSettings& settings, Eigen::VectorXd& x, Eigen::VectorXd& v,
                            Eigen::VectorXd& lastFree, const std::vector<int>* only = nullptr);

// A resting pass for particles that another contact pushed into a collider
// after resolveColliderContacts: the path lastFree → x finds the face entered,
// the particle is put back on it and its approach (with Coulomb friction)
// removed. Updates lastFree; returns the contacts and the particles still
// entering a collider after maxImpacts passes.
ContactCount pushOutOfColliders(const std::vector<Collider>& colliders, const Eigen::VectorXd& inverseMass,
                       const Eigen::VectorXd& radius, const ContactSettings& settings, Eigen::VectorXd& x,
                       Eigen::VectorXd& v, Eigen::VectorXd& lastFree);

}  // namespace particles

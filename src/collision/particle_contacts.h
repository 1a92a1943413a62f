#pragma once
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "contact_types.h"
#include "particles/collider.h"
#include "particles/collision.h"

namespace particles {

// Disc–disc contact between collidable particles, with a uniform-grid broad
// phase so the cost stays linear in the number of particles. With impacts,
// the discs' impacts on each other and on the colliders are taken in the
// order of their times within the step (each on the paths the discs follow
// then): a pair that meets exchanges the impulse j = −(1 + e) u_n / (w_i + w_j)
// (e = ContactSettings::particleRestitution)
// at the time of impact (u_n the approach speed along the line of centres
// then), a collider impact is resolveColliderContacts'. A pair touching or
// overlapping at the step's end is resting: its approach is removed and its
// overlap split in proportion to inverse mass, which keeps momentum and the
// centre of mass.
class ParticleContacts {
 public:
  ParticleContacts();
  ~ParticleContacts();
  ParticleContacts(ParticleContacts&&) noexcept;
  ParticleContacts& operator=(ParticleContacts&&) noexcept;

  // impacts: the continuous pass of a step, from `start` (the colliders may be
  // empty); without, only the resting contacts at the step's end. lastFree
  // (may be null) receives the discs' end positions after their impacts, as
  // resolveColliderContacts' does. Returns the number of contacts resolved and
  // the discs that ran out of maxImpacts.
  // The pairs found touching are kept; resolveResting goes over them again
  // (alternating the order, which carries a push through a stack in both
  // directions) without a new broad phase, and returns the largest speed
  // change it made.
  ContactCount resolve(const std::vector<int>& collidable, const std::vector<Collider>& colliders,
                       const StepStart& start, const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                       const ContactSettings& settings, bool impacts, Eigen::VectorXd& x, Eigen::VectorXd& v,
                       Eigen::VectorXd* lastFree = nullptr);
  double resolveResting(const Eigen::VectorXd& inverseMass, const Eigen::VectorXd& radius,
                        const ContactSettings& settings, bool reverse, Eigen::VectorXd& x, Eigen::VectorXd& v);
  int touchingPairs() const { return static_cast<int>(touching_.size()); }

 private:
  // Pairs of collidable discs near enough to meet this step, as indices into `collidable`.
  void findCandidatePairs(const std::vector<int>& collidable, const Eigen::VectorXd& x, double cell);
  ContactCount resolveImpacts(const std::vector<int>& collidable, const std::vector<Collider>& colliders,
                              const StepStart& start, const Eigen::VectorXd& inverseMass,
                              const Eigen::VectorXd& radius, const ContactSettings& settings, Eigen::VectorXd& x,
                              Eigen::VectorXd& v, Eigen::VectorXd* lastFree);

  std::vector<std::pair<int, int>> touching_;  // pairs found in contact by the last resolve
  struct Scratch;  // broad phase and event queue, kept between steps to avoid allocation
  std::unique_ptr<Scratch> scratch_;
};

}  // namespace particles

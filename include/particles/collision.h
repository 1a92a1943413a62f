#pragma once
// Collisions, resolved after each whole step (never inside integrator stages).
#include <vector>

#include <Eigen/Core>

namespace particles {

// An axis-aligned rectangular obstacle. A particle found inside is moved to the
// nearest face; its normal velocity v_n becomes −s·v_n and its tangential
// velocity is scaled by (1 − friction). (The seed report scales both axes and
// takes both signs from the nearest edges, which reflects a particle that only
// grazes a face along the other axis too; here only the face normal reflects.)
struct Wall {
  Eigen::Vector2d min{0.0, 0.0};
  Eigen::Vector2d max{0.0, 0.0};
  double restitution = 0.5;  // s in [0, 1]: fraction of normal speed kept
  double friction = 0.0;     // in [0, 1]: fraction of tangential speed removed

  void validate() const;  // throws naming the bad field
};

// Pushes every particle out of every wall (particles as discs of radius[i],
// 0 for a point). Pinned particles (inverse mass 0) are never moved.
void resolveWallContacts(const std::vector<Wall>& walls, const Eigen::VectorXd& inverseMass,
                         const Eigen::VectorXd& radius, Eigen::VectorXd& x, Eigen::VectorXd& v);

// Disc–disc contact between collidable particles, with a uniform-grid broad
// phase so the cost stays linear in the number of particles. Overlapping pairs
// are separated along the line of centres in proportion to inverse mass and
// exchange the impulse j = −(1 + e) v_n / (w_i + w_j) when approaching.
class ParticleContacts {
 public:
  double restitution = 0.5;  // e in [0, 1]

  // Returns the number of contacts resolved.
  int resolve(const std::vector<int>& collidable, const Eigen::VectorXd& inverseMass,
              const Eigen::VectorXd& radius, Eigen::VectorXd& x, Eigen::VectorXd& v);

 private:
  // Broad-phase scratch, kept between steps to avoid allocation.
  std::vector<Eigen::Vector2i> cells_;
  std::vector<int> bucket_, order_, bucketStart_, fill_;
};

}  // namespace particles

#pragma once
// A contact as the narrow phase finds it and the solver relaxes it: one
// feature of up to two particles against an obstacle, with the row
//   J = [β₀ n, β₁ n]   (J v: the speed at which the feature separates)
// and a gap g(x) ≥ 0 that the position stage keeps and re-evaluates where the
// particles are (contact_solver.h). Every kind of contact is this one record,
// so that the solver switches on no kind: each kind differs only in how its
// gap, normal and weights follow the particles (Contact::evaluate).
//
//   kind        particles   β               gap
//   Collider    i           (1, 0)          n·(x_i − p): the plane of the face entered,
//                                           p on the collider grown by the particle's radius
//   DiscPair    i, j        (1, −1)         |x_i − x_j| − (r_i + r_j), n = (x_i − x_j)/|x_i − x_j|
//                                           (n·(x_i − x_j) − r_i − r_j with n kept while the
//                                           pair is past each other along it)
//   EdgeCorner  i, j        (1 − b, b)      N·(x_b − q) − r_c: the edge point x_b = (1 − b) x_i + b x_j
//                                           facing the corner q (b its place along the edge), N the
//                                           edge's unit normal on the side away from q, r_c the
//                                           collider's rounding radius
#include <cstdint>

#include <Eigen/Core>

namespace particles {

enum class ContactKind : std::uint8_t { Collider, DiscPair, EdgeCorner };

struct Contact {
  ContactKind kind = ContactKind::Collider;
  int particle[2] = {-1, -1};    // particle[1] < 0 for a collider contact
  double beta[2] = {1.0, 0.0};   // J's weights
  Eigen::Vector2d normal{0.0, 1.0};  // unit: the direction that opens the gap
  Eigen::Vector2d point{0.0, 0.0};   // Collider: a point of the contact plane; EdgeCorner: the corner q
  double reach = 0.0;            // DiscPair: r_i + r_j; EdgeCorner: r_c
  double side = 1.0;             // EdgeCorner: +1 when N is the edge's left normal, −1 the right
  double friction = 0.0;         // Coulomb μ
  double restitution = 0.0;      // e
  double bounce = 0.0;           // the normal row's velocity target (> 0: a bounce)
  bool swept = false;            // the feature's path entered the obstacle during the step (not only near it)
  std::uint64_t key = 0;         // the same contact in the next step has the same key (warm start)

  // The gap at positions x (2n), with the normal and weights made those of
  // x (a collider's plane is fixed for the step).
  double evaluate(const Eigen::VectorXd& x);
  // The gap at positions x along the present normal and weights, linearised:
  // Σ β_k n·x_k less the offset of the obstacle (what a velocity along J
  // closes at the rate J v).
  double linearGap(const Eigen::VectorXd& x) const;
  int count() const { return particle[1] < 0 ? 1 : 2; }
};

// Warm-start keys: the kind in the top bits, then the features' indices.
inline std::uint64_t colliderContactKey(int particle, int collider) {
  return (std::uint64_t{0} << 62) | (static_cast<std::uint64_t>(particle) << 20) | static_cast<std::uint64_t>(collider);
}
inline std::uint64_t discPairKey(int i, int j) {
  return (std::uint64_t{1} << 62) | (static_cast<std::uint64_t>(i) << 31) | static_cast<std::uint64_t>(j);
}
inline std::uint64_t edgeCornerKey(int edge, int collider, int corner) {
  return (std::uint64_t{2} << 62) | (static_cast<std::uint64_t>(edge) << 30) |
         (static_cast<std::uint64_t>(collider) << 10) | static_cast<std::uint64_t>(corner);
}

}  // namespace particles

#pragma once
// The signed area of a closed ring of particles (a cloth's face, a soft
// body's outline) and its derivatives, shared by the forces that act on an
// area (forces/face_area.h, forces/pressure.h) and their position forms.
//
// With the ring's corners x_0 … x_{n−1} (x_n = x_0) and a × b = a_x b_y − a_y b_x,
//   A = ½ Σ_k x_k × x_{k+1}                       (the shoelace formula),
// positive when the corners run counter-clockwise. With P the turn by +90°
// (P v = (−v_y, v_x)),
//   ∂A/∂x_k = ½ P (x_{k−1} − x_{k+1}),
//   ∂²A/∂x_k ∂x_{k+1} = −½ P,   ∂²A/∂x_k ∂x_{k−1} = ½ P   (every other block 0),
// a constant Hessian, symmetric since Pᵀ = −P. A rigid motion leaves A as it
// is, so the gradient's entries sum to zero and exert no torque.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace particles {

// A of the ring `ring` (particle indices, n ≥ 3) at positions x (2n entries of
// the system's layout); the ring as n indices from `ring`, or as a vector.
double ringArea(const Eigen::VectorXd& x, const int* ring, std::size_t n);
inline double ringArea(const Eigen::VectorXd& x, const std::vector<int>& ring) {
  return ringArea(x, ring.data(), ring.size());
}

// ∂A/∂x_k of corner k of the ring.
Eigen::Vector2d ringAreaGradientAt(const Eigen::VectorXd& x, const std::vector<int>& ring, std::size_t k);

// A, and ∂A/∂x_k for each corner k of the ring into gradient (resized to n).
double ringAreaGradient(const Eigen::VectorXd& x, const std::vector<int>& ring,
                        std::vector<Eigen::Vector2d>& gradient);

// The 2×2 block ∂²A/∂x_k ∂x_l between corners k and l of a ring of n corners.
Eigen::Matrix2d ringAreaHessianBlock(int k, int l, int n);

// ∇A W ∇Aᵀ: how fast the area answers a push along its own gradient, with w
// the inverse masses (0 for pinned corners).
double ringAreaWeight(const std::vector<Eigen::Vector2d>& gradient, const std::vector<int>& ring,
                      const Eigen::VectorXd& inverseMass);

// Checks a ring for a force's constructor: at least three corners, no
// particle twice; throws std::invalid_argument naming `what`.
void requireRing(const char* what, const std::vector<int>& ring);

}  // namespace particles

#pragma once
// Faces whose area is held above a floor: what keeps a 2D mass-spring cloth
// from staying folded over itself. A grid of springs has as many rest states
// turned over as the right way round (a cell's mirror image has the same
// side and diagonal lengths), so a cloth folded over is a local minimum of
// its springs' energy with the folded faces inverted (negative signed area).
// This force gives an inverted or crushed face an energy that only turning
// it back the right way round releases; it is zero while a face keeps more
// than a fraction s of its rest area, so it changes nothing of a cloth that
// hangs, swings or stretches (its rest strain and stable dt are as without it).
//
// On each face, a ring of corners (counter-clockwise at rest) with signed
// area A (forces/polygon_area.h) and rest area A₀ > 0, with stiffness k
// (force / length, as a spring's), floor s in [0, 1] and C = A/A₀ − s:
//   E = ½ k A₀ C²   and   f_k = −k C ∂A/∂x_k     while C < 0,
//   E = 0           and   f = 0                   while C ≥ 0
// (C¹ at C = 0). A face turned over entirely (A = −A₀) is pushed back with
// k (1 + s) |∂A/∂x_k| at each corner, |∂A/∂x_k| = |x_{k+1} − x_{k−1}|/2.
// Jacobians, with H the constant Hessian of A:
//   ∂f_k/∂x_l = −(k/A₀) ∂A/∂x_k ∂A/∂x_lᵀ − k C H_kl,   ∂f/∂v = 0;
// the definite form keeps the first (Gauss–Newton) term alone.
// XPBD projects each face as a one-sided compliant constraint C ≥ 0 with
// α = 1/(k A₀) (xpbd/area.h).
//
// One force holds every face of a surface (as the wind holds every edge), so
// a cloth's faces cost one call per evaluation.
#include <vector>

#include "particles/force.h"

namespace particles {

struct AreaFace {
  std::vector<int> ring;  // at least three distinct particles
  double restArea = 0.0;  // A₀ > 0, world units²
};

class FaceAreaForce : public Force {
 public:
  // stiffness ≥ 0, floor in [0, 1], every face a ring with A₀ > 0. Throws
  // std::invalid_argument naming the bad field (and the face).
  FaceAreaForce(std::vector<AreaFace> faces, double stiffness, double floor);

  const char* type() const override { return "face-area"; }
  void apply(const Phase& s, Eigen::VectorXd& f) const override;
  bool hasPotential() const override { return true; }
  double potential(const Phase& s) const override;
  std::vector<int> particles() const override;
  bool hasJacobians() const override { return true; }
  void addJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  void addDefiniteJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const override;
  // A face with a torn side is no face any more: it is dropped, and the
  // links between its corners that are not its sides (its diagonals) break
  // with it, so that a cloth tears along a line of faces: the next side
  // along the rip takes the load the face carried, and tears next.
  bool dropLinks(const LinkSet& broken) override;
  void linksBreakingWith(const LinkSet& broken, std::vector<std::array<int, 2>>& more) const override;

  const std::vector<AreaFace>& faces() const { return faces_; }
  double stiffness() const { return stiffness_; }
  double floor() const { return floor_; }
  // C = A/A₀ − s of one face at positions x.
  double slack(const AreaFace& face, const Eigen::VectorXd& x) const;

 private:
  void addJacobiansImpl(const Phase& s, bool definite, Triplets& dfdx) const;
  std::vector<AreaFace> faces_;
  double stiffness_;  // k, force / length
  double floor_;      // s: the fraction of A₀ below which a face is pushed
};

}  // namespace particles

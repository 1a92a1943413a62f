#pragma once
// A face's area floor (forces/face_area.h) in position form: a one-sided
// compliant constraint.
#include <vector>

#include <Eigen/Core>

#include "xpbd/multiplier.h"

namespace particles {

// On the face's ring, with A its signed area (forces/polygon_area.h), A₀ its
// rest area and s the floor:
//   C = A/A₀ − s ≥ 0,   ∇_k C = ∂A/∂x_k / A₀,
// with α = 1/(k A₀) (the force's E = ½ k A₀ C²) and no damping. Only a face
// below its floor is pushed: the multiplier accumulated over the substep
// stays ≥ 0 (Δλ is clipped at −λ), as for a contact, so a face above its
// floor is left alone.
struct CompliantArea {
  std::vector<int> ring;
  double restArea = 1.0;  // A₀
  double floor = 0.0;     // s
  Compliance compliance;
};

// One projection on the flat position arrays; lambda is this face's
// multiplier of the substep.
void projectArea(const CompliantArea& c, const Eigen::VectorXd& w, Eigen::VectorXd& x, double& lambda);

}  // namespace particles

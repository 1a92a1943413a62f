#include "particles/forces/drag.h"

#include "particles/check.h"

namespace particles {

DragForce::DragForce(double damping) : damping_(damping) {
  requireNonNegative("drag damping", damping);
}

void DragForce::apply(const Phase& s, Eigen::VectorXd& f) const {
  for (int i = 0; i < s.size(); ++i)
    if (s.inverseMass[i] > 0.0) f.segment<2>(2 * i) -= damping_ * s.velocity(i);
}

void DragForce::addJacobians(const Phase& s, Triplets&, Triplets& dfdv) const {
  for (int i = 0; i < s.size(); ++i) {
    if (s.inverseMass[i] == 0.0) continue;
    dfdv.emplace_back(2 * i, 2 * i, -damping_);
    dfdv.emplace_back(2 * i + 1, 2 * i + 1, -damping_);
  }
}

}  // namespace particles

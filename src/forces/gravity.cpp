#include "particles/forces/gravity.h"

#include "particles/check.h"

namespace particles {

GravityForce::GravityForce(const Eigen::Vector2d& g) : g_(g) {
  requireFinite("gravity.x", g.x());
  requireFinite("gravity.y", g.y());
}

void GravityForce::apply(const Phase& s, Eigen::VectorXd& f) const {
  for (int i = 0; i < s.size(); ++i)
    if (s.inverseMass[i] > 0.0) f.segment<2>(2 * i) += s.mass[i] * g_;
}

double GravityForce::potential(const Phase& s) const {
  double e = 0.0;
  for (int i = 0; i < s.size(); ++i)
    if (s.inverseMass[i] > 0.0) e -= s.mass[i] * g_.dot(s.position(i));
  return e;
}

}  // namespace particles

#include "xpbd/angle.h"

#include "particles/forces/angular_spring.h"

namespace particles {

void projectAngle(const CompliantAngle& c, const Eigen::VectorXd& w, const Eigen::VectorXd& xn,
                  Eigen::VectorXd& x, double& lambda) {
  const Eigen::Vector2d zero = Eigen::Vector2d::Zero();
  const AngularSpringKernel k = angularSpringKernel(x.segment<2>(2 * c.p[0]), x.segment<2>(2 * c.p[1]),
                                                    x.segment<2>(2 * c.p[2]), zero, zero, zero);
  double weight = 0.0, displacement = 0.0;
  for (int n = 0; n < 3; ++n) {
    const int q = c.p[n];
    weight += w[q] * k.gradient[n].squaredNorm();
    displacement += k.gradient[n].dot(x.segment<2>(2 * q) - xn.segment<2>(2 * q));
  }
  if (weight == 0.0) return;  // a collapsed arm, or all three pinned
  const double dl = multiplierStep(angleDifference(k.angle, c.restAngle), displacement, c.compliance, lambda,
                                   inverseDenominator(weight, c.compliance));
  lambda += dl;
  for (int n = 0; n < 3; ++n) x.segment<2>(2 * c.p[n]) += (w[c.p[n]] * dl) * k.gradient[n];
}

}  // namespace particles

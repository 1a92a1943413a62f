#include "particles/forces/angular_spring.h"

#include <cmath>

#include "particles/check.h"

namespace particles {

namespace {
constexpr double kPi = 3.14159265358979323846;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }
}  // namespace

double angleDifference(double angle, double restAngle) {
  double d = std::remainder(angle - restAngle, 2.0 * kPi);  // in [−π, π]
  if (d <= -kPi) d += 2.0 * kPi;
  return d;
}

AngularSpringKernel angularSpringKernel(const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                                        const Eigen::Vector2d& x3, const Eigen::Vector2d& v1,
                                        const Eigen::Vector2d& v2, const Eigen::Vector2d& v3) {
  AngularSpringKernel k;
  const Eigen::Vector2d a = x1 - x2, b = x3 - x2;
  const double aa = a.squaredNorm(), bb = b.squaredNorm();
  k.angle = std::atan2(cross(a, b), a.dot(b));
  if (aa == 0.0 || bb == 0.0) {  // a collapsed arm has no angle to restore
    for (auto& g : k.gradient) g.setZero();
    k.rate = 0.0;
    return k;
  }
  k.gradient[0] = Eigen::Vector2d(a.y(), -a.x()) / aa;
  k.gradient[2] = Eigen::Vector2d(-b.y(), b.x()) / bb;
  k.gradient[1] = -(k.gradient[0] + k.gradient[2]);
  k.rate = k.gradient[0].dot(v1) + k.gradient[1].dot(v2) + k.gradient[2].dot(v3);
  return k;
}

AngularSpringForce::AngularSpringForce(int p1, int p2, int p3, double restAngle, double stiffness,
                                       double damping)
    : p_{p1, p2, p3}, restAngle_(restAngle), stiffness_(stiffness), damping_(damping) {
  requireFinite("angular spring rest angle", restAngle);
  requireNonNegative("angular spring stiffness", stiffness);
  requireNonNegative("angular spring damping", damping);
  if (p1 == p2 || p2 == p3 || p1 == p3)
    throw std::invalid_argument("angular spring needs three distinct particles");
}

void AngularSpringForce::apply(const Phase& s, Eigen::VectorXd& f) const {
  const AngularSpringKernel k =
      angularSpringKernel(s.position(p_[0]), s.position(p_[1]), s.position(p_[2]),
                          s.velocity(p_[0]), s.velocity(p_[1]), s.velocity(p_[2]));
  const double torque = stiffness_ * angleDifference(k.angle, restAngle_) + damping_ * k.rate;
  for (int n = 0; n < 3; ++n) f.segment<2>(2 * p_[n]) -= torque * k.gradient[n];
}

double AngularSpringForce::potential(const Phase& s) const {
  const Eigen::Vector2d a = s.position(p_[0]) - s.position(p_[1]);
  const Eigen::Vector2d b = s.position(p_[2]) - s.position(p_[1]);
  const double d = angleDifference(std::atan2(cross(a, b), a.dot(b)), restAngle_);
  return 0.5 * stiffness_ * d * d;
}

void AngularSpringForce::sketch(const Phase& s, Sketch& out) const {
  // The arms, shortened so that they read as an angle marker at the vertex.
  const Eigen::Vector2d v = s.position(p_[1]);
  out.lines.push_back({v, v + 0.3 * (s.position(p_[0]) - v)});
  out.lines.push_back({v, v + 0.3 * (s.position(p_[2]) - v)});
}

}  // namespace particles

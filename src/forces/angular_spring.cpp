#include "particles/forces/angular_spring.h"

#include <cmath>

#include "particles/check.h"
#include "particles/constants.h"
#include "plane_geometry.h"

namespace particles {

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

void angularSpringJacobian(const Eigen::Vector2d& x1, const Eigen::Vector2d& x2,
                           const Eigen::Vector2d& x3, const Eigen::Vector2d& v1,
                           const Eigen::Vector2d& v2, const Eigen::Vector2d& v3, double restAngle,
                           double stiffness, double damping, bool definite,
                           Eigen::Matrix<double, 6, 6>& dfdx, Eigen::Matrix<double, 6, 6>& dfdv) {
  const AngularSpringKernel k = angularSpringKernel(x1, x2, x3, v1, v2, v3);
  Eigen::Matrix<double, 6, 1> g;
  g << k.gradient[0], k.gradient[1], k.gradient[2];
  dfdv = -damping * g * g.transpose();
  dfdx = -stiffness * g * g.transpose();
  if (definite || g.isZero(0.0)) return;

  const Eigen::Vector2d a = x1 - x2, b = x3 - x2;
  Eigen::Matrix2d R;
  R << 0.0, 1.0, -1.0, 0.0;
  const Eigen::Vector2d ah = a.normalized(), bh = b.normalized();
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  const Eigen::Matrix2d Ga = R * (I - 2.0 * ah * ah.transpose()) / a.squaredNorm();
  const Eigen::Matrix2d Gb = -R * (I - 2.0 * bh * bh.transpose()) / b.squaredNorm();
  Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
  H.block<2, 2>(0, 0) = Ga;
  H.block<2, 2>(0, 2) = -Ga;
  H.block<2, 2>(2, 0) = -Ga;
  H.block<2, 2>(2, 2) = Ga + Gb;
  H.block<2, 2>(2, 4) = -Gb;
  H.block<2, 2>(4, 2) = -Gb;
  H.block<2, 2>(4, 4) = Gb;
  Eigen::Matrix<double, 6, 1> v;
  v << v1, v2, v3;
  const double torque = stiffness * angleDifference(k.angle, restAngle) + damping * k.rate;
  // ∂θ̇/∂x = H v (H symmetric).
  dfdx -= damping * g * (H * v).transpose() + torque * H;
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
  if (!enabled_) return;
  const AngularSpringKernel k =
      angularSpringKernel(s.position(p_[0]), s.position(p_[1]), s.position(p_[2]),
                          s.velocity(p_[0]), s.velocity(p_[1]), s.velocity(p_[2]));
  const double torque = stiffness_ * angleDifference(k.angle, restAngle_) + damping_ * k.rate;
  for (int n = 0; n < 3; ++n) f.segment<2>(2 * p_[n]) -= torque * k.gradient[n];
}

void AngularSpringForce::addJacobiansImpl(const Phase& s, bool definite, Triplets& dfdx,
                                          Triplets& dfdv) const {
  if (!enabled_) return;
  Eigen::Matrix<double, 6, 6> jx, jv;
  angularSpringJacobian(s.position(p_[0]), s.position(p_[1]), s.position(p_[2]),
                        s.velocity(p_[0]), s.velocity(p_[1]), s.velocity(p_[2]), restAngle_,
                        stiffness_, damping_, definite, jx, jv);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) {
          dfdx.emplace_back(2 * p_[a] + r, 2 * p_[b] + c, jx(2 * a + r, 2 * b + c));
          if (damping_ != 0.0) dfdv.emplace_back(2 * p_[a] + r, 2 * p_[b] + c, jv(2 * a + r, 2 * b + c));
        }
}

void AngularSpringForce::addJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const {
  addJacobiansImpl(s, false, dfdx, dfdv);
}

void AngularSpringForce::addDefiniteJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const {
  addJacobiansImpl(s, true, dfdx, dfdv);
}

double AngularSpringForce::potential(const Phase& s) const {
  if (!enabled_) return 0.0;
  const Eigen::Vector2d a = s.position(p_[0]) - s.position(p_[1]);
  const Eigen::Vector2d b = s.position(p_[2]) - s.position(p_[1]);
  const double d = angleDifference(std::atan2(cross(a, b), a.dot(b)), restAngle_);
  return 0.5 * stiffness_ * d * d;
}

bool AngularSpringForce::dropLinks(const LinkSet& broken) {
  if (!enabled_ || !(broken.contains(p_[0], p_[1]) || broken.contains(p_[1], p_[2]))) return false;
  enabled_ = false;
  return true;
}

void AngularSpringForce::sketch(const Phase& s, Sketch& out) const {
  if (!enabled_) return;
  // The arms, shortened so that they read as an angle marker at the vertex.
  const Eigen::Vector2d v = s.position(p_[1]);
  out.lines.push_back({v, v + 0.3 * (s.position(p_[0]) - v)});
  out.lines.push_back({v, v + 0.3 * (s.position(p_[2]) - v)});
}

}  // namespace particles

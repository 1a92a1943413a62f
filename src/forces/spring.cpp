#include "particles/forces/spring.h"

#include <algorithm>

#include "particles/check.h"

namespace particles {

Eigen::Vector2d springForce(const Eigen::Vector2d& l, const Eigen::Vector2d& ldot, double rest,
                            double stiffness, double damping) {
  const double length = l.norm();
  if (length == 0.0) return Eigen::Vector2d::Zero();  // direction undefined
  const Eigen::Vector2d u = l * (1.0 / length);  // one division (the batch's vector loops are bound by them)
  return -(stiffness * (length - rest) + damping * ldot.dot(u)) * u;
}

// With u = l/|l|, P = I − u uᵀ and s = k_s(|l| − r) + k_d l̇·u:
//   f = −s u,  ∂u/∂l = P/|l|,  ∂(l̇·u)/∂l = P l̇/|l|,
//   ∂f/∂l = −k_s u uᵀ − s P/|l| − k_d u (P l̇)ᵀ/|l|,   ∂f/∂l̇ = −k_d u uᵀ.
namespace {

// The spring's axis: |l|, u = l/|l| and u uᵀ. Without one (l = 0, direction
// undefined) both Jacobians are set to 0 and it returns false.
struct Axis {
  double length;
  Eigen::Vector2d u;
  Eigen::Matrix2d uu;
};

bool axisOf(const Eigen::Vector2d& l, Axis& axis, Eigen::Matrix2d& dfdl, Eigen::Matrix2d& dfdldot) {
  axis.length = l.norm();
  if (axis.length == 0.0) {
    dfdl.setZero();
    dfdldot.setZero();
    return false;
  }
  axis.u = l / axis.length;
  axis.uu = axis.u * axis.u.transpose();
  return true;
}

}  // namespace

void springJacobian(const Eigen::Vector2d& l, const Eigen::Vector2d& ldot, double rest,
                    double stiffness, double damping, Eigen::Matrix2d& dfdl,
                    Eigen::Matrix2d& dfdldot) {
  Axis axis;
  if (!axisOf(l, axis, dfdl, dfdldot)) return;
  const auto& [length, u, uu] = axis;
  const Eigen::Matrix2d P = Eigen::Matrix2d::Identity() - uu;
  const double s = stiffness * (length - rest) + damping * ldot.dot(u);
  dfdl = -stiffness * uu - (s / length) * P - (damping / length) * u * (P * ldot).transpose();
  dfdldot = -damping * uu;
}

SpringForce::SpringForce(int i, int j, double restLength, double stiffness, double damping)
    : i_(i), j_(j), rest_(restLength), stiffness_(stiffness), damping_(damping) {
  requirePositive("spring rest length", restLength);
  requireNonNegative("spring stiffness", stiffness);
  requireNonNegative("spring damping", damping);
  if (i == j) throw std::invalid_argument("spring joins particle " + std::to_string(i) + " to itself");
}

void SpringForce::apply(const Phase& s, Eigen::VectorXd& f) const {
  if (!enabled_) return;
  const Eigen::Vector2d fi = springForce(s.position(i_) - s.position(j_),
                                         s.velocity(i_) - s.velocity(j_), rest_, stiffness_, damping_);
  f.segment<2>(2 * i_) += fi;
  f.segment<2>(2 * j_) -= fi;
}

double SpringForce::potential(const Phase& s) const {
  if (!enabled_) return 0.0;
  const double stretch = (s.position(i_) - s.position(j_)).norm() - rest_;
  return 0.5 * stiffness_ * stretch * stretch;
}

void springDefiniteJacobian(const Eigen::Vector2d& l, double rest, double stiffness,
                            double damping, Eigen::Matrix2d& dfdl, Eigen::Matrix2d& dfdldot) {
  Axis axis;
  if (!axisOf(l, axis, dfdl, dfdldot)) return;
  const auto& [length, u, uu] = axis;
  const double transverse = stiffness * std::max(0.0, 1.0 - rest / length);
  dfdl = -stiffness * uu - transverse * (Eigen::Matrix2d::Identity() - uu);
  dfdldot = -damping * uu;
}

void SpringForce::addJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const {
  if (!enabled_) return;
  Eigen::Matrix2d dl, dldot;
  springJacobian(s.position(i_) - s.position(j_), s.velocity(i_) - s.velocity(j_), rest_,
                 stiffness_, damping_, dl, dldot);
  addBlocks(dl, dldot, dfdx, dfdv);
}

void SpringForce::addDefiniteJacobians(const Phase& s, Triplets& dfdx, Triplets& dfdv) const {
  if (!enabled_) return;
  Eigen::Matrix2d dl, dldot;
  springDefiniteJacobian(s.position(i_) - s.position(j_), rest_, stiffness_, damping_, dl, dldot);
  addBlocks(dl, dldot, dfdx, dfdv);
}

void SpringForce::addBlocks(const Eigen::Matrix2d& dl, const Eigen::Matrix2d& dldot,
                            Triplets& dfdx, Triplets& dfdv) const {
  // f_i depends on x_i with +∂f/∂l and on x_j with −∂f/∂l; f_j = −f_i.
  const int idx[2] = {i_, j_};
  const double sign[2] = {1.0, -1.0};
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b)
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) {
          const double s2 = sign[a] * sign[b];
          dfdx.emplace_back(2 * idx[a] + r, 2 * idx[b] + c, s2 * dl(r, c));
          if (damping_ != 0.0) dfdv.emplace_back(2 * idx[a] + r, 2 * idx[b] + c, s2 * dldot(r, c));
        }
}

bool SpringForce::dropLinks(const LinkSet& broken) {
  if (!enabled_ || !broken.contains(i_, j_)) return false;
  enabled_ = false;
  return true;
}

void SpringForce::sketch(const Phase& s, Sketch& out) const {
  if (!enabled_) return;
  out.lines.push_back({s.position(i_), s.position(j_)});
}

}  // namespace particles

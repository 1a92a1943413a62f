#include "particles/forces/pressure.h"

#include <cmath>

#include "particles/check.h"
#include "particles/forces/polygon_area.h"

namespace particles {

double PressureLaw::energy(double area) const {
  const double floorArea = kFloor * restArea;
  if (area >= floorArea) return -pressure * restArea * std::log(area / restArea);
  return -pressure * restArea * std::log(kFloor) - at(floorArea) * (area - floorArea);
}

PressureForce::PressureForce(std::vector<int> ring, double restArea, double pressure)
    : ring_(std::move(ring)), law_{restArea, pressure} {
  requireRing("pressure force", ring_);
  requirePositive("pressure rest area", restArea);
  requireNonNegative("pressure", pressure);
}

void PressureForce::apply(const Phase& s, Eigen::VectorXd& f) const {
  if (!enabled_) return;
  const double p = law_.at(ringArea(s.x, ring_));
  for (std::size_t k = 0; k < ring_.size(); ++k) f.segment<2>(2 * ring_[k]) += p * ringAreaGradientAt(s.x, ring_, k);
}

double PressureForce::potential(const Phase& s) const {
  return enabled_ ? law_.energy(ringArea(s.x, ring_)) : 0.0;
}

void PressureForce::addJacobiansImpl(const Phase& s, bool definite, Triplets& dfdx) const {
  if (!enabled_) return;
  std::vector<Eigen::Vector2d> gradient;
  const double area = ringAreaGradient(s.x, ring_, gradient);
  const double p = law_.at(area), slope = law_.slope(area);
  const int n = static_cast<int>(ring_.size());
  for (int k = 0; k < n; ++k)
    for (int l = 0; l < n; ++l) {
      Eigen::Matrix2d block = slope * gradient[k] * gradient[l].transpose();
      if (!definite) block += p * ringAreaHessianBlock(k, l, n);
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) dfdx.emplace_back(2 * ring_[k] + r, 2 * ring_[l] + c, block(r, c));
    }
}

void PressureForce::addJacobians(const Phase& s, Triplets& dfdx, Triplets&) const {
  addJacobiansImpl(s, false, dfdx);
}

void PressureForce::addDefiniteJacobians(const Phase& s, Triplets& dfdx, Triplets&) const {
  addJacobiansImpl(s, true, dfdx);
}

bool PressureForce::dropLinks(const LinkSet& broken) {
  if (!enabled_) return false;
  const std::size_t n = ring_.size();
  for (std::size_t k = 0; k < n; ++k)
    if (broken.contains(ring_[k], ring_[(k + 1) % n])) {
      enabled_ = false;
      return true;
    }
  return false;
}

void PressureForce::sketch(const Phase& s, Sketch& out) const {
  if (!enabled_) return;
  const std::size_t n = ring_.size();
  for (std::size_t k = 0; k < n; ++k) out.lines.push_back({s.position(ring_[k]), s.position(ring_[(k + 1) % n])});
}

}  // namespace particles

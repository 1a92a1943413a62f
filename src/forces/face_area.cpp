#include "particles/forces/face_area.h"

#include <algorithm>
#include <string>

#include "particles/check.h"
#include "particles/forces/polygon_area.h"

namespace particles {

FaceAreaForce::FaceAreaForce(std::vector<AreaFace> faces, double stiffness, double floor)
    : faces_(std::move(faces)), stiffness_(stiffness), floor_(floor) {
  requireNonNegative("face-area stiffness", stiffness);
  requireInRange("face-area floor", floor, 0.0, 1.0);
  for (std::size_t k = 0; k < faces_.size(); ++k) {
    const std::string name = "face-area face " + std::to_string(k);
    requireRing(name.c_str(), faces_[k].ring);
    requirePositive((name + " rest area").c_str(), faces_[k].restArea);
  }
}

double FaceAreaForce::slack(const AreaFace& face, const Eigen::VectorXd& x) const {
  return ringArea(x, face.ring) / face.restArea - floor_;
}

void FaceAreaForce::apply(const Phase& s, Eigen::VectorXd& f) const {
  for (const AreaFace& face : faces_) {
    const double C = slack(face, s.x);
    if (C >= 0.0) continue;
    for (std::size_t k = 0; k < face.ring.size(); ++k)
      f.segment<2>(2 * face.ring[k]) -= stiffness_ * C * ringAreaGradientAt(s.x, face.ring, k);
  }
}

double FaceAreaForce::potential(const Phase& s) const {
  double energy = 0.0;
  for (const AreaFace& face : faces_) {
    const double C = std::min(slack(face, s.x), 0.0);
    energy += 0.5 * stiffness_ * face.restArea * C * C;
  }
  return energy;
}

std::vector<int> FaceAreaForce::particles() const {
  std::vector<int> all;
  for (const AreaFace& face : faces_) all.insert(all.end(), face.ring.begin(), face.ring.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

void FaceAreaForce::addJacobiansImpl(const Phase& s, bool definite, Triplets& dfdx) const {
  std::vector<Eigen::Vector2d> gradient;
  for (const AreaFace& face : faces_) {
    const double C = ringAreaGradient(s.x, face.ring, gradient) / face.restArea - floor_;
    if (C >= 0.0) continue;
    const int n = static_cast<int>(face.ring.size());
    for (int k = 0; k < n; ++k)
      for (int l = 0; l < n; ++l) {
        Eigen::Matrix2d block = -(stiffness_ / face.restArea) * gradient[k] * gradient[l].transpose();
        if (!definite) block -= stiffness_ * C * ringAreaHessianBlock(k, l, n);
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c) dfdx.emplace_back(2 * face.ring[k] + r, 2 * face.ring[l] + c, block(r, c));
      }
  }
}

void FaceAreaForce::addJacobians(const Phase& s, Triplets& dfdx, Triplets&) const {
  addJacobiansImpl(s, false, dfdx);
}

void FaceAreaForce::addDefiniteJacobians(const Phase& s, Triplets& dfdx, Triplets&) const {
  addJacobiansImpl(s, true, dfdx);
}

namespace {
bool sideBroken(const AreaFace& face, const LinkSet& broken) {
  const std::size_t n = face.ring.size();
  for (std::size_t k = 0; k < n; ++k)
    if (broken.contains(face.ring[k], face.ring[(k + 1) % n])) return true;
  return false;
}
}  // namespace

bool FaceAreaForce::dropLinks(const LinkSet& broken) {
  const std::size_t before = faces_.size();
  faces_.erase(std::remove_if(faces_.begin(), faces_.end(), [&](const AreaFace& face) { return sideBroken(face, broken); }),
               faces_.end());
  return faces_.size() != before;
}

void FaceAreaForce::linksBreakingWith(const LinkSet& broken, std::vector<std::array<int, 2>>& more) const {
  for (const AreaFace& face : faces_) {
    if (!sideBroken(face, broken)) continue;
    const std::size_t n = face.ring.size();
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 2; b < n; ++b)
        if (!(a == 0 && b == n - 1)) more.push_back({face.ring[a], face.ring[b]});  // not a side
  }
}

}  // namespace particles

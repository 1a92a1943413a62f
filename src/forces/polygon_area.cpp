#include "particles/forces/polygon_area.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "plane_geometry.h"

namespace particles {

namespace {
Eigen::Vector2d corner(const Eigen::VectorXd& x, int i) { return x.segment<2>(2 * i); }
Eigen::Vector2d turned(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }  // P v
}  // namespace

double ringArea(const Eigen::VectorXd& x, const int* ring, std::size_t n) {
  double twice = 0.0;
  // The terms in ring order, the last one closing the ring (no division per corner).
  for (std::size_t k = 0; k < n; ++k) twice += cross(corner(x, ring[k]), corner(x, ring[k + 1 == n ? 0 : k + 1]));
  return 0.5 * twice;
}

Eigen::Vector2d ringAreaGradientAt(const Eigen::VectorXd& x, const std::vector<int>& ring, std::size_t k) {
  const std::size_t n = ring.size();
  return 0.5 * turned(corner(x, ring[k == 0 ? n - 1 : k - 1]) - corner(x, ring[k + 1 == n ? 0 : k + 1]));
}

double ringAreaGradient(const Eigen::VectorXd& x, const std::vector<int>& ring,
                        std::vector<Eigen::Vector2d>& gradient) {
  gradient.resize(ring.size());
  for (std::size_t k = 0; k < ring.size(); ++k) gradient[k] = ringAreaGradientAt(x, ring, k);
  return ringArea(x, ring);
}

Eigen::Matrix2d ringAreaHessianBlock(int k, int l, int n) {
  Eigen::Matrix2d P;
  P << 0.0, -1.0, 1.0, 0.0;
  Eigen::Matrix2d block = Eigen::Matrix2d::Zero();
  if (l == (k + 1) % n) block -= 0.5 * P;
  if (l == (k + n - 1) % n) block += 0.5 * P;
  return block;
}

double ringAreaWeight(const std::vector<Eigen::Vector2d>& gradient, const std::vector<int>& ring,
                      const Eigen::VectorXd& inverseMass) {
  double weight = 0.0;
  for (std::size_t k = 0; k < ring.size(); ++k) weight += inverseMass[ring[k]] * gradient[k].squaredNorm();
  return weight;
}

void requireRing(const char* what, const std::vector<int>& ring) {
  if (ring.size() < 3)
    throw std::invalid_argument(std::string(what) + " needs a ring of at least 3 particles, got " +
                                std::to_string(ring.size()));
  std::vector<int> sorted = ring;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    throw std::invalid_argument(std::string(what) + " names a particle twice in its ring");
}

}  // namespace particles

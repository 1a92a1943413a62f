// Broad phase against colliders: which particles' paths over the step come
// near any collider at all.
#include <algorithm>
#include <array>
#include <vector>

#include "particles/collision.h"

namespace particles {

void markNearColliders(const std::vector<Collider>& colliders, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1,
                       double margin, std::vector<char>& near) {
  const int n = static_cast<int>(x1.size() / 2);
  near.assign(n, 0);
  const double* S = x0.data();
  const double* X = x1.data();
  // Colliders in chunks whose grown boxes (lo x, lo y, hi x, hi y) or
  // half-plane rows (n, n·p + margin) sit on the stack; each particle's path
  // box is made once per chunk and tested with a few comparisons per collider.
  constexpr std::size_t kChunk = 8;
  for (std::size_t first = 0; first < colliders.size(); first += kChunk) {
    const std::size_t last = std::min(colliders.size(), first + kChunk);
    std::array<std::array<double, 4>, kChunk> boxes{}, planes{};
    std::size_t boxCount = 0, planeCount = 0;
    for (std::size_t k = first; k < last; ++k) {
      const Collider& c = colliders[k];
      Eigen::Vector2d lo, hi;
      if (c.bounds(lo, hi))
        boxes[boxCount++] = {lo.x() - margin, lo.y() - margin, hi.x() + margin, hi.y() + margin};
      else
        planes[planeCount++] = {c.normal.x(), c.normal.y(), c.normal.dot(c.points[0]) + margin, 0.0};
    }
    for (int i = 0; i < n; ++i) {
      if (near[i]) continue;
      const double ax = S[2 * i], ay = S[2 * i + 1], bx = X[2 * i], by = X[2 * i + 1];
      const double loX = std::min(ax, bx), hiX = std::max(ax, bx), loY = std::min(ay, by), hiY = std::max(ay, by);
      bool hit = false;
      for (std::size_t k = 0; k < boxCount && !hit; ++k) {
        const std::array<double, 4>& b = boxes[k];
        hit = loY <= b[3] && hiY >= b[1] && loX <= b[2] && hiX >= b[0];
      }
      // A half-plane n·(x − p) ≤ 0: near when either end is within margin of it.
      for (std::size_t k = 0; k < planeCount && !hit; ++k) {
        const std::array<double, 4>& p = planes[k];
        hit = std::min(p[0] * ax + p[1] * ay, p[0] * bx + p[1] * by) <= p[2];
      }
      near[i] = hit;
    }
  }
}

}  // namespace particles

#include "starting_overlap.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "particles/cancel.h"

namespace scenes {

namespace {

// The particles sorted into a grid of side × side cells over their bounding
// box (side = ⌈√n⌉: about one particle a cell) by a counting sort: cell k
// holds order[start[k]] … order[start[k + 1] − 1]. An axis along which the
// particles do not spread, or whose extent overflows, has one cell.
class ParticleGrid {
 public:
  explicit ParticleGrid(const Eigen::VectorXd& x) {
    const int n = static_cast<int>(x.size() / 2);
    if (n == 0) return;
    side_ = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))));
    const auto points = Eigen::Map<const Eigen::Matrix2Xd>(x.data(), 2, n);
    min_ = points.rowwise().minCoeff();
    const Eigen::Vector2d extent = points.rowwise().maxCoeff() - min_;
    for (int axis = 0; axis < 2; ++axis) {
      cells_[axis] = extent[axis] > 0.0 && std::isfinite(extent[axis]) ? side_ : 1;
      size_[axis] = cells_[axis] > 1 ? extent[axis] / cells_[axis] : 1.0;
    }
    std::vector<int> cell(n);
    start_.assign(static_cast<std::size_t>(cells_[0]) * cells_[1] + 1, 0);
    for (int i = 0; i < n; ++i) {
      cell[i] = index(cellAlong(0, x[2 * i]), cellAlong(1, x[2 * i + 1]));
      ++start_[cell[i] + 1];
    }
    for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    order_.resize(n);
    std::vector<int> next(start_.begin(), start_.end() - 1);
    for (int i = 0; i < n; ++i) order_[next[cell[i]]++] = i;  // ascending indices within each cell
  }

  // visit(i) for every particle in a cell that meets the box [lo, hi].
  template <class Visit>
  void forEachIn(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, Visit&& visit) const {
    if (order_.empty()) return;
    const int x0 = cellAlong(0, lo.x()), x1 = cellAlong(0, hi.x());
    const int y0 = cellAlong(1, lo.y()), y1 = cellAlong(1, hi.y());
    for (int cy = y0; cy <= y1; ++cy)
      for (int cx = x0; cx <= x1; ++cx)
        for (int k = start_[index(cx, cy)], end = start_[index(cx, cy) + 1]; k < end; ++k) visit(order_[k]);
  }

 private:
  // The cell along an axis holding coordinate v, clamped to the grid (a box
  // reaching beyond the particles meets the edge cells).
  int cellAlong(int axis, double v) const {
    const double c = std::floor((v - min_[axis]) / size_[axis]);
    return static_cast<int>(std::clamp(std::isnan(c) ? 0.0 : c, 0.0, cells_[axis] - 1.0));
  }
  int index(int cx, int cy) const { return cy * cells_[0] + cx; }

  int side_ = 1;
  int cells_[2] = {1, 1};
  Eigen::Vector2d min_ = Eigen::Vector2d::Zero(), size_ = Eigen::Vector2d::Ones();
  std::vector<int> start_, order_;
};

}  // namespace

double startingOverlapTolerance(const Eigen::Vector2d& x) { return 1e-6 * std::max(1.0, x.norm()); }

std::optional<StartingOverlap> firstStartingOverlap(const particles::ParticleSystem& system, bool cancellable) {
  const std::vector<particles::Collider>& colliders = system.colliders();
  if (colliders.empty() || system.size() == 0) return std::nullopt;
  const Eigen::VectorXd& x = system.positions();
  const Eigen::VectorXd& radius = system.radii();
  const double reach = radius.maxCoeff();  // a particle farther than this from a collider's box is outside it
  const ParticleGrid grid(x);
  std::optional<StartingOverlap> first;
  particles::CancelPoll cancel(4096);
  const auto test = [&](int i, std::size_t c) {
    if (cancellable && cancel.poll()) throw particles::Cancelled();
    if (first && i >= first->particle) return;  // colliders come in order: not an earlier overlap
    const Eigen::Vector2d p = system.position(i);
    const double depth = radius[i] - colliders[c].distance(p).distance;
    if (depth > startingOverlapTolerance(p)) first = StartingOverlap{i, c, depth};
  };
  for (std::size_t c = 0; c < colliders.size(); ++c) {
    if (cancellable) particles::throwIfCancelled();
    Eigen::Vector2d lo, hi;
    if (!colliders[c].bounds(lo, hi)) {  // a half-plane: every particle
      for (int i = 0; i < system.size(); ++i) test(i, c);
      continue;
    }
    lo.array() -= reach;
    hi.array() += reach;
    grid.forEachIn(lo, hi, [&](int i) {
      const Eigen::Vector2d p = system.position(i);
      if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) test(i, c);
    });
  }
  return first;
}

}  // namespace scenes

#include "particles/collision.h"

#include <algorithm>
#include <cmath>

#include "particles/check.h"

namespace particles {

void Wall::validate() const {
  requireFinite("wall min.x", min.x());
  requireFinite("wall min.y", min.y());
  requireFinite("wall max.x", max.x());
  requireFinite("wall max.y", max.y());
  if (!(max.x() > min.x()) || !(max.y() > min.y()))
    throw std::invalid_argument("wall max must exceed min on both axes, got min (" +
                                formatValue(min.x()) + ", " + formatValue(min.y()) + ") max (" +
                                formatValue(max.x()) + ", " + formatValue(max.y()) + ")");
  requireInRange("wall restitution", restitution, 0.0, 1.0);
  requireInRange("wall friction", friction, 0.0, 1.0);
}

void resolveWallContacts(const std::vector<Wall>& walls, const Eigen::VectorXd& inverseMass,
                         const Eigen::VectorXd& radius, Eigen::VectorXd& x, Eigen::VectorXd& v) {
  const int n = static_cast<int>(inverseMass.size());
  for (int i = 0; i < n; ++i) {
    if (inverseMass[i] == 0.0) continue;
    for (const Wall& wall : walls) {
      const double r = radius[i];
      const Eigen::Vector2d lo = wall.min.array() - r, hi = wall.max.array() + r;
      Eigen::Vector2d p = x.segment<2>(2 * i);
      if (!(p.x() > lo.x() && p.x() < hi.x() && p.y() > lo.y() && p.y() < hi.y())) continue;
      // Depth to each face: left, right, bottom, top; leave by the shallowest.
      const double depth[4] = {p.x() - lo.x(), hi.x() - p.x(), p.y() - lo.y(), hi.y() - p.y()};
      const int face = static_cast<int>(std::min_element(depth, depth + 4) - depth);
      const int axis = face / 2;
      const double normalSign = (face % 2 == 0) ? -1.0 : 1.0;
      p[axis] = (face % 2 == 0) ? lo[axis] : hi[axis];
      x.segment<2>(2 * i) = p;
      Eigen::Vector2d vel = v.segment<2>(2 * i);
      const double vn = vel[axis] * normalSign;
      if (vn < 0.0) {  // approaching: reflect the normal part, rub the tangential part
        vel[axis] = -wall.restitution * vel[axis];
        vel[1 - axis] *= (1.0 - wall.friction);
        v.segment<2>(2 * i) = vel;
      }
    }
  }
}

int ParticleContacts::resolve(const std::vector<int>& collidable, const Eigen::VectorXd& inverseMass,
                              const Eigen::VectorXd& radius, Eigen::VectorXd& x, Eigen::VectorXd& v) {
  // A public field rather than a constructor argument, so it is checked where it is used.
  requireInRange("particle contact restitution", restitution, 0.0, 1.0);
  const int count = static_cast<int>(collidable.size());
  if (count < 2) return 0;
  double maxRadius = 0.0;
  for (int i : collidable) maxRadius = std::max(maxRadius, radius[i]);
  const double cell = 2.0 * maxRadius;  // any overlapping pair lies in neighbouring cells

  // Broad phase: hash each disc's cell into a table of 2·count buckets, and
  // sort particles by bucket (counting sort, linear time).
  int buckets = 1;
  while (buckets < 2 * count) buckets <<= 1;
  // Cell coordinates are clamped so that a far-flung (or exploded) particle
  // cannot overflow the integer conversion; such particles share edge cells.
  auto toCell = [&](double coordinate) {
    const double c = std::floor(coordinate / cell);
    return static_cast<int>(std::isfinite(c) ? std::clamp(c, -1e9, 1e9) : 1e9);
  };
  auto cellOf = [&](int i) { return Eigen::Vector2i(toCell(x[2 * i]), toCell(x[2 * i + 1])); };
  auto bucketOf = [&](const Eigen::Vector2i& c) {
    const unsigned long long h = static_cast<unsigned long long>(c.x()) * 73856093ULL ^
                                 static_cast<unsigned long long>(c.y()) * 19349663ULL;
    return static_cast<int>(h & static_cast<unsigned long long>(buckets - 1));
  };
  std::vector<Eigen::Vector2i>& cells = cells_;
  cells.resize(count);
  bucket_.resize(count);
  bucketStart_.assign(buckets + 1, 0);
  for (int a = 0; a < count; ++a) {
    cells[a] = cellOf(collidable[a]);
    bucket_[a] = bucketOf(cells[a]);
    ++bucketStart_[bucket_[a] + 1];
  }
  for (int b = 0; b < buckets; ++b) bucketStart_[b + 1] += bucketStart_[b];
  order_.resize(count);
  fill_.assign(bucketStart_.begin(), bucketStart_.end() - 1);
  for (int a = 0; a < count; ++a) order_[fill_[bucket_[a]]++] = a;

  int contacts = 0;
  for (int a = 0; a < count; ++a) {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const Eigen::Vector2i c = cells[a] + Eigen::Vector2i(dx, dy);
        const int bucket = bucketOf(c);
        for (int s = bucketStart_[bucket]; s < bucketStart_[bucket + 1]; ++s) {
          const int b = order_[s];
          if (b <= a || cells[b] != c) continue;  // each pair once; skip hash collisions
          const int i = collidable[a], j = collidable[b];
          const double wi = inverseMass[i], wj = inverseMass[j], wsum = wi + wj;
          if (wsum == 0.0) continue;
          Eigen::Vector2d d = x.segment<2>(2 * i) - x.segment<2>(2 * j);
          const double reach = radius[i] + radius[j];
          const double dist2 = d.squaredNorm();
          if (dist2 >= reach * reach) continue;
          const double dist = std::sqrt(dist2);
          const Eigen::Vector2d n = dist > 0.0 ? Eigen::Vector2d(d / dist) : Eigen::Vector2d(1.0, 0.0);
          const double overlap = reach - dist;
          x.segment<2>(2 * i) += (overlap * wi / wsum) * n;
          x.segment<2>(2 * j) -= (overlap * wj / wsum) * n;
          const double vn = (v.segment<2>(2 * i) - v.segment<2>(2 * j)).dot(n);
          if (vn < 0.0) {
            const double impulse = -(1.0 + restitution) * vn / wsum;
            v.segment<2>(2 * i) += impulse * wi * n;
            v.segment<2>(2 * j) -= impulse * wj * n;
          }
          ++contacts;
        }
      }
  }
  return contacts;
}

}  // namespace particles

// Each contact kind's gap, normal and weights where the particles are (contact.h).
#include "contact.h"

#include <algorithm>
#include <cmath>

namespace particles {

double Contact::evaluate(const Eigen::VectorXd& x) {
  const Eigen::Vector2d xi = x.segment<2>(2 * particle[0]);
  switch (kind) {
    case ContactKind::Collider:
      return normal.dot(xi - point);
    case ContactKind::DiscPair: {
      const Eigen::Vector2d d = xi - x.segment<2>(2 * particle[1]);
      const double along = normal.dot(d);
      // Past each other (the pair met on the way and went through): the
      // normal of the approach holds, so the pair goes back the way it came.
      if (!(along > 0.0)) return along - reach;
      normal = d / d.norm();
      return d.norm() - reach;
    }
    case ContactKind::EdgeCorner: {
      const Eigen::Vector2d e = x.segment<2>(2 * particle[1]) - xi;
      const double length2 = e.squaredNorm();
      if (length2 > 0.0) {
        const double b = std::clamp((point - xi).dot(e) / length2, 0.0, 1.0);
        beta[0] = 1.0 - b;
        beta[1] = b;
        normal = side * Eigen::Vector2d(-e.y(), e.x()) / std::sqrt(length2);
      }
      return normal.dot(beta[0] * xi + beta[1] * x.segment<2>(2 * particle[1]) - point) - reach;
    }
  }
  return 0.0;
}

double Contact::linearGap(const Eigen::VectorXd& x) const {
  double along = 0.0;
  for (int k = 0; k < count(); ++k) along += beta[k] * normal.dot(x.segment<2>(2 * particle[k]));
  switch (kind) {
    case ContactKind::Collider:
      return along - normal.dot(point);
    case ContactKind::DiscPair:
      return along - reach;
    case ContactKind::EdgeCorner:
      return along - normal.dot(point) - reach;
  }
  return along;
}

}  // namespace particles

#include "camera.h"

#include <algorithm>
#include <cmath>

namespace demo {

void Camera::reset(const Eigen::Vector2d& viewMin, const Eigen::Vector2d& viewMax) {
  min_ = viewMin;
  max_ = viewMax;
  sceneSize_ = viewMax - viewMin;
}

void Camera::zoom(double factor, const Eigen::Vector2d& at) {
  if (!(factor > 0.0) || !std::isfinite(factor) || !at.allFinite()) return;
  const double current = sceneSize_.x() / (max_.x() - min_.x());
  factor = std::clamp(current * factor, minZoom, maxZoom) / current;
  min_ = at + (min_ - at) / factor;
  max_ = at + (max_ - at) / factor;
}

void Camera::pan(const Eigen::Vector2d& worldDelta) {
  if (!worldDelta.allFinite()) return;
  min_ += worldDelta;
  max_ += worldDelta;
}

void Camera::frame(Eigen::Vector2d lo, Eigen::Vector2d hi) {
  if (!lo.allFinite() || !hi.allFinite()) return;
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  Eigen::Vector2d half = 0.5 * (hi - lo) * (1.0 + 2.0 * frameMargin);
  half = half.cwiseMax(0.05 * sceneSize_).cwiseMin(0.5 * sceneSize_ / minZoom);
  min_ = centre - half;
  max_ = centre + half;
}

bool particleBounds(const particles::ParticleSystem& system, Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
  bool any = false;
  for (int i = 0; i < system.size(); ++i) {
    const Eigen::Vector2d x = system.position(i);
    if (!x.allFinite()) continue;
    lo = any ? lo.cwiseMin(x) : x;
    hi = any ? hi.cwiseMax(x) : x;
    any = true;
  }
  return any;
}

}  // namespace demo

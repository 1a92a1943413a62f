#pragma once
// What part of the world the panes show: a world rectangle that each pane
// fits at one scale on both axes (view.h's fitView). It starts at the scene's
// view; the wheel zooms about the cursor, a drag pans, frame() fits a box.
#include <Eigen/Core>

#include "particles/particle_system.h"

namespace demo {

class Camera {
 public:
  // Zoom is kept within these factors of the scene's own view.
  static constexpr double minZoom = 1e-3, maxZoom = 1e4;
  static constexpr double wheelFactor = 1.2;  // zoom per wheel click
  static constexpr double frameMargin = 0.1;  // frame(): border, as a fraction of the box

  void reset(const Eigen::Vector2d& viewMin, const Eigen::Vector2d& viewMax);
  // factor > 1 zooms in; the world point `at` stays under the same pixel
  // (fitView centres the rectangle, so scaling it about `at` keeps at's pixel).
  void zoom(double factor, const Eigen::Vector2d& at);
  void pan(const Eigen::Vector2d& worldDelta);
  // Shows the box lo..hi with a margin, no smaller than a tenth of the scene's view.
  void frame(Eigen::Vector2d lo, Eigen::Vector2d hi);

  const Eigen::Vector2d& min() const { return min_; }
  const Eigen::Vector2d& max() const { return max_; }

 private:
  Eigen::Vector2d min_{-1.0, -1.0}, max_{1.0, 1.0};
  Eigen::Vector2d sceneSize_{2.0, 2.0};
};

// The bounding box of the particles with finite positions; false when there are none.
bool particleBounds(const particles::ParticleSystem& system, Eigen::Vector2d& lo, Eigen::Vector2d& hi);

}  // namespace demo

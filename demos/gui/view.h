#pragma once
// Where things go on screen: panes in the window, and the mapping between a
// pane's pixels and world coordinates that keeps the world's aspect ratio.
#include <vector>

#include <Eigen/Core>

namespace demo {

// A rectangle of window pixels, origin at the top-left corner (as GLUT's mouse
// coordinates and PNG rows), y growing downward.
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
  bool contains(int px, int py) const {
    return px >= x && px < x + width && py >= y && py < y + height;
  }
};

// The scene's view rectangle centred in a pane at one scale on both axes; the
// pane's extra width or height shows more of the world rather than stretching it.
struct ViewTransform {
  PixelRect pane;
  Eigen::Vector2d worldMin{-1.0, -1.0}, worldMax{1.0, 1.0};  // what the pane shows
  double pixelsPerUnit = 1.0;

  Eigen::Vector2d toWorld(double px, double py) const {
    return {worldMin.x() + (px - pane.x) / pixelsPerUnit, worldMax.y() - (py - pane.y) / pixelsPerUnit};
  }
  Eigen::Vector2d toPixel(const Eigen::Vector2d& w) const {
    return {pane.x + (w.x() - worldMin.x()) * pixelsPerUnit, pane.y + (worldMax.y() - w.y()) * pixelsPerUnit};
  }
};

ViewTransform fitView(const PixelRect& pane, const Eigen::Vector2d& viewMin, const Eigen::Vector2d& viewMax);

// Splits an area into `count` panes (1: whole; 2: side by side; 3–4: a 2×2 grid).
std::vector<PixelRect> splitPanes(const PixelRect& area, int count);

}  // namespace demo

#include "view.h"

#include <algorithm>

namespace demo {

ViewTransform fitView(const PixelRect& pane, const Eigen::Vector2d& viewMin, const Eigen::Vector2d& viewMax) {
  ViewTransform t;
  t.pane = pane;
  const Eigen::Vector2d size = viewMax - viewMin, centre = 0.5 * (viewMin + viewMax);
  const double width = std::max(pane.width, 1), height = std::max(pane.height, 1);
  t.pixelsPerUnit = std::min(width / size.x(), height / size.y());
  const Eigen::Vector2d half(0.5 * width / t.pixelsPerUnit, 0.5 * height / t.pixelsPerUnit);
  t.worldMin = centre - half;
  t.worldMax = centre + half;
  return t;
}

std::vector<PixelRect> splitPanes(const PixelRect& area, int count) {
  if (count <= 1) return {area};
  const int columns = 2, rows = count == 2 ? 1 : 2;
  const int w = area.width / columns, h = area.height / rows;
  std::vector<PixelRect> panes;
  for (int k = 0; k < count; ++k) {
    const int c = k % columns, r = k / columns;
    // The last column and row take the remainder pixels; a 1-pixel gap separates panes.
    panes.push_back({area.x + c * w + (c > 0), area.y + r * h + (r > 0),
                     (c == columns - 1 ? area.width - c * w : w) - (c > 0),
                     (r == rows - 1 ? area.height - r * h : h) - (r > 0)});
  }
  return panes;
}

}  // namespace demo

// Build mode's marks over the scene: the selected object's outline, the
// gesture being drawn (its points so far and a line to the pointer) and a
// ring on the particle the next point would snap to.
#include <cmath>

#include "app.h"
#include "build_geometry.h"
#include "particles/constants.h"

namespace demo {

namespace {
constexpr double selectionRingPixels = 10.0;
constexpr double pointRingPixels = 5.0;
constexpr double snapRingPixels = 12.0;
constexpr int ringSegments = 40;

void ring(ShapeBatch& lines, const Eigen::Vector2d& centre, double radius, Rgb colour) {
  for (int k = 0; k < ringSegments; ++k) {
    const double a = 2.0 * particles::kPi * k / ringSegments, b = 2.0 * particles::kPi * (k + 1) / ringSegments;
    lines.line(centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a)),
               centre + radius * Eigen::Vector2d(std::cos(b), std::sin(b)), colour);
  }
}

// A sketch's lines and circles; a circle of radius 0 (a particle) as a ring of `pointRadius`.
void addSketch(ShapeBatch& lines, const particles::Sketch& sketch, double pointRadius, Rgb colour) {
  for (const auto& line : sketch.lines) lines.line(line.a, line.b, colour);
  for (const auto& circle : sketch.circles)
    ring(lines, circle.centre, circle.radius > 0.0 ? circle.radius : pointRadius, colour);
}
}  // namespace

void App::drawBuildOverlay(const ViewTransform& view) {
  const particles::ParticleSystem& system = panes_.front()->system();
  const double pixel = 1.0 / view.pixelsPerUnit;
  ShapeBatch selection, gesture;
  const Rgb selected = palette::buildSelection, drawn = palette::buildGesture;
  if (build_.selection && refersToObject(build_.history.current(), *build_.selection))
    addSketch(selection,
              outlineOf(build_.history.current(), system, *build_.selection, (view.worldMax - view.worldMin).norm()),
              selectionRingPixels * pixel, selected);
  const std::vector<BuildPoint>& pending = build_.pending();
  for (std::size_t k = 0; k < pending.size(); ++k) {
    ring(gesture, pending[k].at, pointRingPixels * pixel, drawn);
    if (k > 0) gesture.line(pending[k - 1].at, pending[k].at, drawn);
  }
  if (const std::optional<Eigen::Vector2d>& cursor = build_.cursor()) {
    if (!pending.empty()) gesture.line(pending.back().at, *cursor, drawn);
    const BuildPoint next = build_.pointAt(*cursor, system, buildPickRadius(), !pending.empty());
    if (next.particle) ring(gesture, next.at, snapRingPixels * pixel, drawn);
  }
  Painter& painter = renderer_.painter();
  painter.beginPane(view, windowHeight_);
  painter.lines(selection, 3.0, true);
  painter.lines(gesture, 2.0, true);
  painter.endPane();
}

}  // namespace demo

// Build mode's marks over the scene: the selected object's outline, the
// gesture being drawn (its points so far and a line to the pointer) and a
// ring on the particle the next point would snap to.
#include <GL/gl.h>

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

// Line segments in world units, drawn in one call.
struct Lines {
  std::vector<float> xy;
  void add(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    for (const Eigen::Vector2d& p : {a, b}) {
      xy.push_back(static_cast<float>(p.x()));
      xy.push_back(static_cast<float>(p.y()));
    }
  }
  void ring(const Eigen::Vector2d& centre, double radius) {
    for (int k = 0; k < ringSegments; ++k) {
      const double a = 2.0 * particles::kPi * k / ringSegments, b = 2.0 * particles::kPi * (k + 1) / ringSegments;
      add(centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a)),
          centre + radius * Eigen::Vector2d(std::cos(b), std::sin(b)));
    }
  }
  void draw(Rgb colour, float width) const {
    if (xy.empty()) return;
    glLineWidth(width);
    glColor4ub(colour.r, colour.g, colour.b, 255);
    glVertexPointer(2, GL_FLOAT, 0, xy.data());
    glDrawArrays(GL_LINES, 0, static_cast<GLsizei>(xy.size() / 2));
  }
};

// A sketch's lines and circles; a circle of radius 0 (a particle) as a ring of `pointRadius`.
void addSketch(Lines& lines, const particles::Sketch& sketch, double pointRadius) {
  for (const auto& line : sketch.lines) lines.add(line.a, line.b);
  for (const auto& circle : sketch.circles) lines.ring(circle.centre, circle.radius > 0.0 ? circle.radius : pointRadius);
}
}  // namespace

void App::drawBuildOverlay(const ViewTransform& view) {
  const particles::ParticleSystem& system = panes_.front()->system();
  const double pixel = 1.0 / view.pixelsPerUnit;
  Lines selection, gesture;
  if (build_.selection && refersToObject(build_.history.current(), *build_.selection))
    addSketch(selection,
              outlineOf(build_.history.current(), system, *build_.selection, (view.worldMax - view.worldMin).norm()),
              selectionRingPixels * pixel);
  const std::vector<BuildPoint>& pending = build_.pending();
  for (std::size_t k = 0; k < pending.size(); ++k) {
    gesture.ring(pending[k].at, pointRingPixels * pixel);
    if (k > 0) gesture.add(pending[k - 1].at, pending[k].at);
  }
  if (const std::optional<Eigen::Vector2d>& cursor = build_.cursor()) {
    if (!pending.empty()) gesture.add(pending.back().at, *cursor);
    const BuildPoint next = build_.pointAt(*cursor, system, buildPickRadius(), !pending.empty());
    if (next.particle) gesture.ring(next.at, snapRingPixels * pixel);
  }
  const PixelRect& p = view.pane;
  glViewport(p.x, windowHeight_ - p.y - p.height, p.width, p.height);
  glScissor(p.x, windowHeight_ - p.y - p.height, p.width, p.height);
  glEnable(GL_SCISSOR_TEST);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(view.worldMin.x(), view.worldMax.x(), view.worldMin.y(), view.worldMax.y(), -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glEnableClientState(GL_VERTEX_ARRAY);
  selection.draw(palette::buildSelection, 3.0f);
  gesture.draw(palette::buildGesture, 2.0f);
  glDisableClientState(GL_VERTEX_ARRAY);
  glDisable(GL_SCISSOR_TEST);
}

}  // namespace demo

#include "build_mode.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "build_geometry.h"

namespace demo {

namespace {
// The grid point nearest v, as the decimal a user reads: k·g rounded to 15
// significant digits (6 × 0.05 is 0.30000000000000004 in binary; the point
// is 0.3, and so its fields show and its file says).
double onGrid(double v, double grid) {
  char text[32];
  std::snprintf(text, sizeof text, "%.15g", std::round(v / grid) * grid);
  return std::strtod(text, nullptr);
}
}  // namespace

BuildMode::BuildMode() {
  for (const BuildTool& tool : buildTools()) fields_.push_back(tool.defaults());
}

void BuildMode::setActive(bool active) {
  active_ = active;
  cancelGesture();
}

void BuildMode::selectTool(std::size_t index) {
  if (index >= buildTools().size()) return;
  tool_ = index;
  cancelGesture();
}

std::optional<std::size_t> BuildMode::toolForKey(unsigned char key) const {
  for (std::size_t k = 0; k < buildTools().size(); ++k)
    if (buildTools()[k].key == key) return k;
  return std::nullopt;
}

std::optional<std::size_t> BuildMode::toolNamed(const std::string& name) const {
  for (std::size_t k = 0; k < buildTools().size(); ++k) {
    std::string dashed = buildTools()[k].name;
    for (char& c : dashed) c = c == ' ' ? '-' : c;
    if (name == buildTools()[k].name || name == dashed) return k;
  }
  return std::nullopt;
}

const Json& BuildMode::particleFields() const { return fields_.at(*toolNamed("particle")); }

BuildPoint BuildMode::pointAt(const Eigen::Vector2d& world, const particles::ParticleSystem& system,
                              double pickRadius, bool release) const {
  // The point's index in its gesture: a click's or drag's press is 0, a
  // drag's release 1; each click of a series counts on from those before it.
  const std::size_t index = tool().gesture == Gesture::Clicks ? pending_.size() : (release ? 1 : 0);
  BuildPoint point;
  point.raw = world;
  if (tool().snapsToParticle(index))
    if (const std::optional<int> particle = nearestParticle(system, world, pickRadius)) {
      point.particle = particle;
      point.at = system.position(*particle);
      return point;
    }
  point.at = grid > 0.0 ? Eigen::Vector2d(onGrid(world.x(), grid), onGrid(world.y(), grid)) : world;
  return point;
}

void BuildMode::press(const BuildPoint& point) {
  pressed_ = true;
  cursor_ = point.raw;
  if (tool().gesture != Gesture::Clicks) pending_ = {point};
}

std::optional<std::vector<BuildPoint>> BuildMode::release(const BuildPoint& point, double pickRadius) {
  if (!pressed_) return std::nullopt;  // a release whose press went elsewhere (the panel)
  pressed_ = false;
  const BuildTool& t = tool();
  if (t.gesture == Gesture::Click) {
    std::vector<BuildPoint> points = pending_;
    pending_.clear();
    return points;
  }
  if (t.gesture == Gesture::Drag) {
    std::vector<BuildPoint> points = {pending_.at(0), point};
    pending_.clear();
    return points;
  }
  // A series of clicks: an open one closes on its first point.
  if (t.points == 0 && pending_.size() >= 3 && (point.raw - pending_.front().at).norm() <= pickRadius)
    return finishClicks();
  pending_.push_back(point);
  if (t.points > 0 && static_cast<int>(pending_.size()) == t.points) return finishClicks();
  return std::nullopt;
}

std::optional<std::vector<BuildPoint>> BuildMode::finishClicks() {
  // Enter closes a gesture of any number of clicks (a polygon's corners); one
  // of a fixed number (an angle spring's three) is done only with all of them.
  const BuildTool& t = tool();
  if (t.gesture != Gesture::Clicks || pending_.empty() || static_cast<int>(pending_.size()) < t.points)
    return std::nullopt;
  std::vector<BuildPoint> points = std::move(pending_);
  pending_.clear();
  return points;
}

void BuildMode::cancelGesture() {
  pending_.clear();
  pressed_ = false;
}

}  // namespace demo

#include "scenes/hourglass.h"

#include <cmath>
#include <memory>

#include "particles/check.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"

namespace scenes {

namespace {
// The glass: its half-width, the height of each bulb's sloping shoulder and straight part.
constexpr double kHalfWidth = 0.3, kShoulder = 0.3, kStraight = 0.3, kWall = 0.008;
}  // namespace

void HourglassParams::validate() const {
  requireAtLeast("grains", grains, 1);
  requireWithinLimit("grains", grains, 2000);
  particles::requirePositive("radius", radius);
  particles::requireInRange("radius", radius, 1e-4, 0.05);
  particles::requirePositive("mass", mass);
  particles::requireInRange("neck", neck, 0.0, 2.0 * kHalfWidth - 0.02);
  particles::requireInRange("restitution", restitution, 0.0, 1.0);
  particles::requireNonNegative("friction", friction);
  particles::requireNonNegative("gravity", gravity);
  // The grains must fit in the upper bulb's straight part, packed on a square grid.
  const int perRow = static_cast<int>((2.0 * (kHalfWidth - kWall) - 2.0 * radius) / (2.2 * radius)) + 1;
  const int rows = (grains + perRow - 1) / perRow;
  if (rows * 2.2 * radius > kStraight + kShoulder - 2.0 * radius)
    throw std::invalid_argument("grains: " + std::to_string(grains) + " grains of radius " + output::formatNumber(radius) +
                                " do not fit in the upper bulb (at most " +
                                std::to_string(perRow * static_cast<int>((kStraight + kShoulder) / (2.2 * radius) - 1)) + ")");
}

HourglassParams HourglassParams::seed() {
  HourglassParams p;
  p.gravity = kSeedGravity;
  p.dt = 0.01;
  return p;
}

Scene buildHourglass(const HourglassParams& p) {
  Scene scene;
  scene.name = "hourglass";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;
  const double w = kHalfWidth, n = 0.5 * p.neck + kWall;
  // The walls, capsules of radius kWall: each bulb's straight sides and its
  // shoulders sloping to the neck at y = 0; a lid and a base.
  auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    particles::Collider c = particles::Collider::capsule(a, b, kWall);
    c.friction = p.friction;
    c.restitution = p.restitution;
    s.addCollider(c);
  };
  for (const double side : {-1.0, 1.0}) {
    for (const double up : {-1.0, 1.0}) {
      wall({side * n, 0.0}, {side * w, up * kShoulder});
      wall({side * w, up * kShoulder}, {side * w, up * (kShoulder + kStraight)});
    }
  }
  wall({-w, kShoulder + kStraight}, {w, kShoulder + kStraight});
  wall({-w, -kShoulder - kStraight}, {w, -kShoulder - kStraight});
  // The grains on a square grid in the upper bulb, from its lid down, each
  // row shifted by a tenth of a grain so that the heap does not stand in columns.
  const double pitch = 2.2 * p.radius, inner = w - kWall - p.radius;
  const int perRow = static_cast<int>(2.0 * inner / pitch) + 1;
  std::vector<Eigen::Vector2d> positions;
  for (int k = 0; k < p.grains; ++k) {
    const int row = k / perRow, col = k % perRow;
    positions.push_back({-inner + col * pitch + 0.1 * p.radius * (row % 2), kShoulder + kStraight - kWall - p.radius - row * pitch});
  }
  const int first = s.addParticles(positions, std::vector<double>(positions.size(), p.mass));
  for (int k = 0; k < p.grains; ++k) s.setCollidable(first + k, p.radius);
  s.contactSettings().particleRestitution = p.restitution;
  addGravity(s, p.gravity);
  const double top = kShoulder + kStraight + 2.0 * kWall;
  scene.viewMin = Eigen::Vector2d(-w - 0.05, -top - 0.03);
  scene.viewMax = Eigen::Vector2d(w + 0.05, top + 0.03);
  return scene;
}

}  // namespace scenes

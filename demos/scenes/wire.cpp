#include "scenes/wire.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "particles/check.h"
#include "particles/constraints/circular_wire.h"
#include "particles/forces/spring.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"
#include "scenes/world.h"

namespace scenes {

void WireParams::validate() const {
  requireAtLeast("beads", beads, 1);
  requireWithinLimit("beads", beads, SceneLimits::particles);
  particles::requirePositive("radius", radius);
  particles::requirePositive("mass", mass);
  particles::requireNonNegative("coupling", coupling);
  particles::requireFinite("gravity", gravity);
}

WireParams WireParams::seed() {
  WireParams p;
  p.beads = 3;
  p.radius = 0.25;
  p.mass = 1.0;
  p.coupling = 0.2;
  p.gravity = kSeedGravity;
  p.dt = 0.01;
  return p;
}

Scene buildWire(const WireParams& p) {
  Scene scene;
  scene.name = "wire";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;

  // Wires 2.4 radii apart in a row centred on the origin; bead k starts
  // 30°·(k + 1) counter-clockwise from the bottom of its wire.
  const double pitch = 2.4 * p.radius;
  for (int k = 0; k < p.beads; ++k) {
    const Eigen::Vector2d centre((k - 0.5 * (p.beads - 1)) * pitch, 0.0);
    const double angle = radians(30.0 * (k + 1));
    const int bead = s.addParticle(centre + p.radius * Eigen::Vector2d(std::sin(angle), -std::cos(angle)), p.mass);
    s.addConstraint(std::make_unique<particles::CircularWireConstraint>(bead, centre, p.radius));
  }
  if (p.coupling > 0.0)
    for (int k = 0; k + 1 < p.beads; ++k) {
      const double rest = (s.position(k) - s.position(k + 1)).norm();
      s.addForce(std::make_unique<particles::SpringForce>(k, k + 1, rest, p.coupling, 0.0));
    }
  addGravity(s, p.gravity);

  // The row of wires, a little margin round them.
  const Eigen::Vector2d half(0.5 * (p.beads - 1) * pitch + 1.3 * p.radius, 1.3 * p.radius);
  scene.viewMin = -half;
  scene.viewMax = half;
  return scene;
}

}  // namespace scenes

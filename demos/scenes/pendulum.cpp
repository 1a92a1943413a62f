#include "scenes/pendulum.h"

#include <cmath>
#include <memory>

#include "particles/check.h"
#include "particles/constraints/circular_wire.h"
#include "scenes/elliptic.h"
#include "scenes/param_fields.h"
#include "scenes/world.h"

namespace scenes {

void PendulumParams::validate() const {
  particles::requirePositive("length", length);
  particles::requireInRange("angle", angle, -179.0, 179.0);
  particles::requirePositive("mass", mass);
  particles::requirePositive("gravity", gravity);
}

PendulumParams PendulumParams::seed() {
  PendulumParams p;
  p.length = 0.5;
  p.angle = 60.0;
  p.mass = 1.0;
  p.gravity = kSeedGravity;
  p.dt = 0.01;
  return p;
}

Scene buildPendulum(const PendulumParams& p) {
  Scene scene;
  scene.name = "pendulum";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;
  const Eigen::Vector2d centre(0.0, 0.0);
  const double theta0 = radians(p.angle);
  const int bead = s.addParticle(centre + p.length * Eigen::Vector2d(std::sin(theta0), -std::cos(theta0)), p.mass);
  s.addConstraint(std::make_unique<particles::CircularWireConstraint>(bead, centre, p.length));
  addGravity(s, p.gravity);
  // The whole wire: the bead can be dragged anywhere on it.
  scene.viewMin = Eigen::Vector2d::Constant(-1.15 * p.length);
  scene.viewMax = Eigen::Vector2d::Constant(1.15 * p.length);
  return scene;
}

double pendulumPeriod(const PendulumParams& p) {
  return 4.0 * std::sqrt(p.length / p.gravity) * ellipticK(std::sin(0.5 * radians(p.angle)));
}

}  // namespace scenes

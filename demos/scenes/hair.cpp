#include "scenes/hair.h"

#include <cmath>
#include <memory>

#include "particles/check.h"
#include "particles/constraints/line.h"
#include "particles/forces/angular_spring.h"
#include "particles/forces/spring.h"
#include "scenes/param_fields.h"
#include "scenes/world.h"

namespace scenes {

void HairParams::validate() const {
  requireAtLeast("curls", curls, 1);
  requireAtLeast("particles", particles, 3);
  particles::requirePositive("rest", rest);
  particles::requirePositive("mass", mass);
  particles::requireNonNegative("stiffness", stiffness);
  particles::requireNonNegative("damping", damping);
  particles::requireInRange("bend-angle", bendAngle, 1.0, 179.0);
  particles::requireNonNegative("bend-stiffness", bendStiffness);
  particles::requireNonNegative("bend-damping", bendDamping);
  particles::requirePositive("radius", radius);
  // Neighbours are rest apart: larger discs would push every link apart.
  if (!(2.0 * radius < rest))
    throw std::invalid_argument("radius must be < rest/2 = " + particles::formatValue(rest / 2) +
                                ", got " + particles::formatValue(radius));
  particles::requireFinite("gravity", gravity);
}

HairParams HairParams::seed() {
  HairParams p;
  p.curls = 6;
  p.particles = 25;
  p.rest = 0.08;
  p.mass = 10.0;
  p.stiffness = 300.0;
  p.damping = 1.0;
  p.bendAngle = 90.0;
  p.bendStiffness = 1.0;
  p.bendDamping = 3.0;
  p.radius = 0.025;
  p.gravity = 0.005;
  p.dt = 0.002;
  return p;
}

Scene buildHair(const HairParams& p) {
  Scene scene;
  scene.name = "hair";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;

  const double theta0 = radians(p.bendAngle);
  // Consecutive links turn by π − θ₀ alternately right and left of straight down.
  const double tilt = 0.5 * (kPi - theta0);
  const Eigen::Vector2d right(p.rest * std::sin(tilt), -p.rest * std::cos(tilt));
  const Eigen::Vector2d left(-right.x(), right.y());
  const double spacing = 2.0 / (p.curls + 1);
  const Eigen::Vector2d rail(0.0, 0.9);

  for (int c = 0; c < p.curls; ++c) {
    Eigen::Vector2d x(-1.0 + spacing * (c + 1), rail.y());
    const int root = s.addParticle(x, p.mass);
    for (int k = 1; k < p.particles; ++k) {
      x += (k % 2 == 1) ? right : left;
      s.addParticle(x, p.mass);
    }
    for (int k = root; k < root + p.particles; ++k) s.setCollidable(k, p.radius);
    for (int k = root; k + 1 < root + p.particles; ++k)
      s.addForce(std::make_unique<particles::SpringForce>(k, k + 1, p.rest, p.stiffness, p.damping));
    // Going right then left, the vertex angle from arm (back) to arm (on) is +θ₀; then −θ₀.
    for (int k = root + 1; k + 1 < root + p.particles; ++k) {
      const double sign = ((k - root) % 2 == 1) ? 1.0 : -1.0;
      s.addForce(std::make_unique<particles::AngularSpringForce>(k - 1, k, k + 1, sign * theta0,
                                                                 p.bendStiffness, p.bendDamping));
    }
    s.addConstraint(std::make_unique<particles::LineConstraint>(root, rail, 0.0));
  }
  addGravity(s, p.gravity);
  return scene;
}

}  // namespace scenes

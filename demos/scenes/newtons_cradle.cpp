#include "scenes/newtons_cradle.h"

#include <cmath>
#include <memory>

#include "particles/check.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"

namespace scenes {

void NewtonsCradleParams::validate() const {
  requireAtLeast("balls", balls, 2);
  requireWithinLimit("balls", balls, 1000);
  particles::requirePositive("radius", radius);
  particles::requirePositive("length", length);
  if (length <= radius) throw std::invalid_argument("length must exceed radius (the rod reaches the ball's centre)");
  particles::requirePositive("mass", mass);
  particles::requireInRange("angle", angle, -90.0, 90.0);
  particles::requireNonNegative("gap", gap);
  particles::requireInRange("restitution", restitution, 0.0, 1.0);
  particles::requireNonNegative("gravity", gravity);
}

NewtonsCradleParams NewtonsCradleParams::seed() {
  NewtonsCradleParams p;
  p.gravity = kSeedGravity;
  p.dt = 0.01;
  return p;
}

Scene buildNewtonsCradle(const NewtonsCradleParams& p) {
  Scene scene;
  scene.name = "newtons-cradle";
  scene.dt = p.dt;
  scene.integrator = "rk4";
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;
  const double pitch = 2.0 * p.radius + p.gap;
  const double left = -0.5 * (p.balls - 1) * pitch, top = 0.5 * p.length;
  const double theta = radians(p.angle);
  for (int k = 0; k < p.balls; ++k) {
    const Eigen::Vector2d pivot(left + k * pitch, top);
    // The first ball swings out to the left by θ₀; the others hang straight.
    const Eigen::Vector2d down = k == 0 ? Eigen::Vector2d(-std::sin(theta), -std::cos(theta)) : Eigen::Vector2d(0.0, -1.0);
    const int anchor = s.addParticle(pivot, p.mass);
    s.setPinned(anchor, true);
    const int ball = s.addParticle(pivot + p.length * down, p.mass);
    s.setCollidable(ball, p.radius);
    s.addConstraint(std::make_unique<particles::RodConstraint>(anchor, ball, p.length));
  }
  s.contactSettings().particleRestitution = p.restitution;
  addGravity(s, p.gravity);
  // The row and the swings out to θ₀ on both sides.
  const double reach = p.length * std::sin(std::abs(theta)) + p.radius;
  const double half = std::max(0.5 * (p.balls - 1) * pitch + reach, 0.6 * p.length + p.radius) * 1.15;
  scene.viewMin = Eigen::Vector2d(-half, top - p.length - 0.35 * half);
  scene.viewMax = Eigen::Vector2d(half, top + 0.25 * half);
  return scene;
}

double cradleImpactSpeed(const NewtonsCradleParams& p) {
  return std::sqrt(2.0 * p.gravity * p.length * (1.0 - std::cos(radians(p.angle))));
}

}  // namespace scenes

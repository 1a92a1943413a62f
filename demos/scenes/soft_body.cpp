#include "scenes/soft_body.h"

#include <cmath>
#include <memory>

#include "particles/check.h"
#include "particles/forces/drag.h"
#include "particles/forces/polygon_area.h"
#include "particles/forces/pressure.h"
#include "particles/forces/spring.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"

namespace scenes {

void SoftBodyParams::validate() const {
  if (bodies != 1 && bodies != 2) throw std::invalid_argument("bodies must be 1 or 2, got " + std::to_string(bodies));
  requireAtLeast("particles", particles, 3);
  requireWithinLimit("particles", particles, SceneLimits::particles / 2);
  particles::requirePositive("radius", radius);
  particles::requirePositive("mass", mass);
  particles::requirePositive("stiffness", stiffness);
  particles::requireNonNegative("damping", damping);
  particles::requireNonNegative("pressure", pressure);
  particles::requireNonNegative("gravity", gravity);
  particles::requireNonNegative("drag", drag);
}

SoftBodyParams SoftBodyParams::seed() {
  SoftBodyParams p;
  p.gravity = kSeedGravity;
  p.dt = 0.01;
  return p;
}

Scene buildSoftBody(const SoftBodyParams& p) {
  Scene scene;
  scene.name = "soft-body";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;
  const int N = p.particles;
  const double side = 2.0 * p.radius * std::sin(particles::kPi / N);
  // Side by side above the floor; the second higher and to the right, so that it lands on the first's shoulder.
  const Eigen::Vector2d centres[2] = {{-0.5 * p.radius, 2.0 * p.radius}, {0.9 * p.radius, 4.6 * p.radius}};
  const double pressures[2] = {p.pressure, 0.25 * p.pressure};
  for (int b = 0; b < p.bodies; ++b) {
    std::vector<Eigen::Vector2d> ring;
    for (int k = 0; k < N; ++k) {
      const double a = 2.0 * particles::kPi * k / N;
      ring.push_back(centres[b] + p.radius * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
    const int first = s.addParticles(ring, std::vector<double>(N, p.mass));
    std::vector<int> indices;
    for (int k = 0; k < N; ++k) {
      indices.push_back(first + k);
      s.setCollidable(first + k, 0.4 * side);  // neighbours a fifth of a side apart at rest
      s.addForce(std::make_unique<particles::SpringForce>(first + k, first + (k + 1) % N, side, p.stiffness, p.damping));
      s.addCollisionEdge(first + k, first + (k + 1) % N);
    }
    const double restArea = particles::ringArea(s.positions(), indices);
    s.addForce(std::make_unique<particles::PressureForce>(indices, restArea, pressures[b]));
  }
  addGravity(s, p.gravity);
  if (p.drag > 0.0) s.addForce(std::make_unique<particles::DragForce>(p.drag));
  // A floor and a ramp rising to the right.
  const double R = p.radius;
  s.addCollider(particles::Collider::box(Eigen::Vector2d(-6.0 * R, -1.0 * R), Eigen::Vector2d(6.0 * R, 0.0)));
  s.addCollider(particles::Collider::polygon({{2.0 * R, 0.0}, {6.0 * R, 0.0}, {6.0 * R, 2.0 * R}}));
  s.addCollider(particles::Collider::box(Eigen::Vector2d(-6.0 * R, 0.0), Eigen::Vector2d(-5.5 * R, 6.0 * R)));
  scene.viewMin = Eigen::Vector2d(-6.2 * R, -1.2 * R);
  scene.viewMax = Eigen::Vector2d(6.2 * R, 6.4 * R);
  return scene;
}

}  // namespace scenes

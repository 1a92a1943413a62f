#include "scenes/capstan.h"

#include <cmath>
#include <memory>

#include <cstdio>

#include "particles/check.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"

namespace scenes {

void CapstanParams::validate() const {
  particles::requireInRange("ratio", ratio, 1.0, 1000.0);
  particles::requireNonNegative("friction", friction);
  particles::requirePositive("load", load);
  particles::requirePositive("radius", radius);
  requireAtLeast("links", links, 6);
  requireWithinLimit("links+1 particles", links + 1LL, SceneLimits::constraints);
  particles::requirePositive("drop", drop);
  particles::requirePositive("rope-mass", ropeMass);
  particles::requireFinite("push", push);
  particles::requireNonNegative("gravity", gravity);
}

CapstanParams CapstanParams::seed() {
  CapstanParams p;
  p.gravity = kSeedGravity;
  p.dt = 0.01;
  return p;
}

double capstanLimit(const CapstanParams& p) { return std::exp(p.friction * particles::kPi); }

Scene buildCapstan(const CapstanParams& p) {
  Scene scene;
  scene.name = "capstan";
  scene.dt = p.dt;
  // Backward Euler holds the rods under the loads' pull while the contacts
  // hold the rope on the pulley; the explicit schemes' constraint drift lets
  // the rods stretch there within a tenth of a second.
  scene.integrator = "implicit-euler";
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;
  // The rope's path: up the left side, half round the top of the pulley, down
  // the right, at the pulley's surface; `links` equal rods along it.
  const double R = p.radius, arc = particles::kPi * R, length = 2.0 * p.drop + arc;
  auto along = [&](double u) -> Eigen::Vector2d {
    if (u < p.drop) return {-R, -p.drop + u};
    if (u < p.drop + arc) {
      const double a = particles::kPi - (u - p.drop) / R;
      return {R * std::cos(a), R * std::sin(a)};
    }
    return {R, -(u - p.drop - arc)};
  };
  std::vector<Eigen::Vector2d> positions;
  for (int k = 0; k <= p.links; ++k) positions.push_back(along(length * k / p.links));
  // Rods join points of the path: each the chord of its stretch, so the
  // rope starts at rest on the pulley without a jerk.
  std::vector<double> masses(positions.size(), p.ropeMass);
  masses.front() = p.load;
  masses.back() = p.ratio * p.load;
  const int first = s.addParticles(positions, masses);
  // Released sliding toward the heavy side at `push`: kinetic friction brings
  // a rope that friction can hold to rest.
  for (int k = 0; k <= p.links; ++k) {
    const double u = length * k / p.links, du = 1e-6 * length;
    const Eigen::Vector2d tangent = (along(std::min(u + du, length)) - along(std::max(u - du, 0.0))).normalized();
    s.setVelocity(first + k, p.push * tangent);
  }
  for (int k = 0; k < p.links; ++k) {
    const double chord = (positions[k + 1] - positions[k]).norm();
    s.addConstraint(std::make_unique<particles::RodConstraint>(first + k, first + k + 1, chord));
    s.addCollisionEdge(first + k, first + k + 1);
  }
  particles::Collider pulley = particles::Collider::disc(Eigen::Vector2d::Zero(), R);
  pulley.friction = p.friction;
  pulley.restitution = 0.0;
  s.addCollider(pulley);
  addGravity(s, p.gravity);
  const double limit = capstanLimit(p);
  char caption[200];
  std::snprintf(caption, sizeof caption, "loads %g : %g kg, mass ratio %.3g %s e^(mu pi) = e^(%g pi) = %.3g: %s",
                p.load, p.ratio * p.load, p.ratio, p.ratio <= limit ? "<=" : ">", p.friction, limit,
                p.ratio <= limit ? "friction can hold it" : "it must slip");
  scene.caption = caption;
  const double half = std::max(1.6 * R, 0.6 * p.drop);
  scene.viewMin = Eigen::Vector2d(-2.2 * half, -p.drop - 0.3 * half);
  scene.viewMax = Eigen::Vector2d(2.2 * half, 1.6 * R + 0.3 * half);
  return scene;
}

}  // namespace scenes

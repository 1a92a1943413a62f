#include "scenes/hair.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "particles/check.h"
#include "particles/constants.h"
#include "particles/constraints/line.h"
#include "particles/forces/angular_spring.h"
#include "particles/forces/drag.h"
#include "particles/forces/spring.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"

namespace scenes {

void HairParams::validate() const {
  requireAtLeast("curls", curls, 1);
  requireAtLeast("particles", particles, 3);
  requireWithinLimit("curls*particles particles", static_cast<long long>(curls) * particles, SceneLimits::particles);
  particles::requirePositive("rest", rest);
  particles::requirePositive("mass", mass);
  particles::requireNonNegative("stiffness", stiffness);
  particles::requireNonNegative("damping", damping);
  if (shape != "ringlet" && shape != "zigzag")
    throw std::invalid_argument("shape must be ringlet or zigzag, got '" + shape + "'");
  if (root != "pinned" && root != "rail")
    throw std::invalid_argument("root must be pinned or rail, got '" + root + "'");
  particles::requireInRange("bend-angle", bendAngle, 1.0, 179.0);
  particles::requireNonNegative("bend-stiffness", bendStiffness);
  particles::requireNonNegative("bend-damping", bendDamping);
  particles::requirePositive("radius", radius);
  // Neighbours are rest apart: larger discs would push every link apart.
  if (!(2.0 * radius < rest))
    throw std::invalid_argument("radius must be < rest/2 = " + particles::formatValue(rest / 2) +
                                ", got " + particles::formatValue(radius));
  particles::requireFinite("gravity", gravity);
  particles::requireNonNegative("drag", drag);
  validateWindTear();
}

HairParams HairParams::seed() {
  HairParams p;
  p.curls = 6;
  p.particles = 25;
  p.rest = 0.08;
  p.mass = 10.0;
  p.stiffness = 300.0;
  p.damping = 1.0;
  p.shape = "zigzag";
  p.root = "rail";
  p.drag = 0.0;
  p.bendAngle = 90.0;
  p.bendStiffness = 1.0;
  p.bendDamping = 3.0;
  p.radius = 0.025;
  // The seed's hair has its own small gravity, a tenth of the seed world's:
  // its curls hang down with little weight against k_s = 1.
  p.gravity = 0.005;
  p.dt = 0.002;  // midpoint diverges by dt = 0.006 and RK4 by 0.008
  return p;
}

double hairRestAngle(const HairParams& p, int curl, int k) {
  const double theta0 = radians(p.bendAngle);
  if (p.shape == "zigzag") return (k % 2 == 1) ? theta0 : -theta0;
  return (curl % 2 == 0) ? theta0 : -theta0;
}

Scene buildHair(const HairParams& p) {
  Scene scene;
  scene.name = "hair";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;

  // A zigzag starts at its rest shape: consecutive links turn by π − θ₀
  // alternately right and left of straight down. A ringlet starts straight
  // down and curls up.
  const double tilt = p.shape == "zigzag" ? 0.5 * (particles::kPi - radians(p.bendAngle)) : 0.0;
  const Eigen::Vector2d right(p.rest * std::sin(tilt), -p.rest * std::cos(tilt));
  const Eigen::Vector2d left(-right.x(), right.y());

  // The zigzag's roots as in the seed's [−1, 1]² view, at 2k/(curls + 1) − 1
  // across and 0.9 up; a ringlet's roots at y = 0, 0.15 strand lengths apart
  // so that neighbouring curls touch, under a view fitted to the hanging hair.
  const double length = (p.particles - 1) * p.rest;
  const bool seedLayout = p.shape == "zigzag";
  const double spacing = seedLayout ? 2.0 / (p.curls + 1) : 0.15 * length;
  const Eigen::Vector2d rail(0.0, seedLayout ? 0.9 : 0.0);
  const double firstX = -0.5 * spacing * (p.curls + 1);
  if (seedLayout) {
    scene.viewMin = Eigen::Vector2d::Constant(-1.0);
    scene.viewMax = Eigen::Vector2d::Constant(1.0);
  } else {
    const double half = 0.5 * std::max(spacing * (p.curls + 1), 0.8 * length);
    const Eigen::Vector2d centre(0.0, -0.3 * length);
    scene.viewMin = centre - Eigen::Vector2d::Constant(half);
    scene.viewMax = centre + Eigen::Vector2d::Constant(half);
  }

  for (int c = 0; c < p.curls; ++c) {
    Eigen::Vector2d x(firstX + spacing * (c + 1), rail.y());
    const int root = s.addParticle(x, p.mass);
    for (int k = 1; k < p.particles; ++k) {
      x += (k % 2 == 1) ? right : left;
      s.addParticle(x, p.mass);
    }
    // The root rides the rail and is no disc: a contact pushing it off the
    // rail would drag the whole strand after it.
    for (int k = root + 1; k < root + p.particles; ++k) s.setCollidable(k, p.radius);
    for (int k = root; k + 1 < root + p.particles; ++k) {
      s.addForce(std::make_unique<particles::SpringForce>(k, k + 1, p.rest, p.stiffness, p.damping));
      scene.windEdges.push_back({k, k + 1});
    }
    for (int k = 1; k + 1 < p.particles; ++k)
      s.addForce(std::make_unique<particles::AngularSpringForce>(root + k - 1, root + k, root + k + 1,
                                                                 hairRestAngle(p, c, k), p.bendStiffness,
                                                                 p.bendDamping));
    if (p.root == "rail") s.addConstraint(std::make_unique<particles::LineConstraint>(root, rail, 0.0));
    else s.setPinned(root, true);
  }
  addGravity(s, p.gravity);
  if (p.drag > 0.0) s.addForce(std::make_unique<particles::DragForce>(p.drag));
  p.addWindAndTearing(s, scene.windEdges);
  return scene;
}

}  // namespace scenes

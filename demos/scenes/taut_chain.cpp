#include "scenes/taut_chain.h"

#include <algorithm>
#include <memory>

#include "particles/check.h"
#include "particles/constraints/circular_wire.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"
#include "scenes/world.h"

namespace scenes {

void TautChainParams::validate() const {
  requireAtLeast("links", links, 1);
  requireWithinLimit("links+1 particles", links + 1LL, SceneLimits::particles);
  particles::requirePositive("separation", separation);
  particles::requirePositive("radius", radius);
  particles::requirePositive("mass", mass);
  particles::parseRodForm(rod);
  particles::requireFinite("gravity", gravity);
}

TautChainParams TautChainParams::seed() {
  TautChainParams p;
  p.links = 8;
  p.separation = 1.2;
  p.radius = 0.2;
  p.mass = 1.0;
  p.rod = "squared";
  p.gravity = kSeedGravity;
  p.dt = 0.01;
  return p;
}

Scene buildTautChain(const TautChainParams& p) {
  Scene scene;
  scene.name = "taut-chain";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;

  // The beads start at the outer points of the wires, as far apart as they
  // can be: the chain of (separation + 2 radius)/links rods is exactly taut.
  const Eigen::Vector2d leftCentre(-0.5 * p.separation, 0.0), rightCentre(0.5 * p.separation, 0.0);
  const Eigen::Vector2d start = leftCentre - Eigen::Vector2d(p.radius, 0.0);
  const Eigen::Vector2d end = rightCentre + Eigen::Vector2d(p.radius, 0.0);
  const int first = addRodChain(s, start, end, p.links, p.mass, particles::parseRodForm(p.rod));
  const int last = first + p.links;
  s.addConstraint(std::make_unique<particles::CircularWireConstraint>(first, leftCentre, p.radius));
  s.addConstraint(std::make_unique<particles::CircularWireConstraint>(last, rightCentre, p.radius));
  addGravity(s, p.gravity);

  const double half = std::max(1.0, 0.6 * (end - start).norm());
  scene.viewMin = Eigen::Vector2d::Constant(-half);
  scene.viewMax = Eigen::Vector2d::Constant(half);
  return scene;
}

}  // namespace scenes

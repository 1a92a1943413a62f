#include "scenes/taut_chain.h"

#include <algorithm>
#include <memory>

#include "particles/check.h"
#include "particles/constraints/circular_wire.h"

namespace scenes {

void TautChainParams::validate() const {
  validateShared(links);
  particles::requirePositive("separation", separation);
  particles::requirePositive("radius", radius);
}

TautChainParams TautChainParams::seed() {
  TautChainParams p;  // the seed's chain: 8 rods between wires of radius 0.2, 1.2 apart
  p.useSeedValues();
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
  const int first = p.addChain(s, start, end, p.links);
  const int last = first + p.links;
  s.addConstraint(std::make_unique<particles::CircularWireConstraint>(first, leftCentre, p.radius));
  s.addConstraint(std::make_unique<particles::CircularWireConstraint>(last, rightCentre, p.radius));

  // Both wires and the chain hanging between them, as deep as it can sag.
  const double span = (end - start).norm();
  scene.viewMin = Eigen::Vector2d(-0.6 * span, -0.55 * span);
  scene.viewMax = Eigen::Vector2d(0.6 * span, p.radius + 0.1 * span);
  return scene;
}

}  // namespace scenes

#include "scenes/rod_chain.h"

#include <algorithm>
#include <memory>

#include "particles/check.h"
#include "particles/constraints/circular_wire.h"

namespace scenes {

void RodChainParams::validate() const {
  validateShared(links);
  particles::requirePositive("length", length);
  particles::requirePositive("radius", radius);
}

RodChainParams RodChainParams::seed() {
  RodChainParams p;  // the seed's chain: 6 rods of 0.12 on a wire of radius 0.25
  p.useSeedValues();
  return p;
}

Scene buildRodChain(const RodChainParams& p) {
  Scene scene;
  scene.name = "rod-chain";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;

  // The wire sits high in the view; the chain starts at its rightmost point.
  const Eigen::Vector2d centre(0.0, 0.4);
  const Eigen::Vector2d start = centre + Eigen::Vector2d(p.radius, 0.0);
  const Eigen::Vector2d end = start + Eigen::Vector2d(p.links * p.length, 0.0);
  const int bead = p.addChain(s, start, end, p.links);
  s.addConstraint(std::make_unique<particles::CircularWireConstraint>(bead, centre, p.radius));

  // The chain can swing to any side of the wire.
  const double reach = p.radius + p.links * p.length;
  // The wire and every place the chain can swing to from it.
  scene.viewMin = centre - Eigen::Vector2d(1.05 * reach, 1.05 * reach);
  scene.viewMax = centre + Eigen::Vector2d(1.05 * reach, p.radius + 0.15 * reach);
  return scene;
}

}  // namespace scenes

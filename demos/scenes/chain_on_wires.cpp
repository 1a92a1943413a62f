#include "scenes/chain_on_wires.h"

#include "particles/check.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"

namespace scenes {

void ChainOnWiresParams::validateShared(int links) const {
  requireAtLeast("links", links, 1);
  requireWithinLimit("links+1 particles", links + 1LL, SceneLimits::particles);
  particles::requirePositive("mass", mass);
  particles::parseRodForm(rod);
  particles::requireFinite("gravity", gravity);
}

void ChainOnWiresParams::useSeedValues() {
  mass = 1.0;
  rod = "squared";
  gravity = kSeedGravity;
  dt = 0.01;
}

int ChainOnWiresParams::addChain(particles::ParticleSystem& system, const Eigen::Vector2d& start,
                                 const Eigen::Vector2d& end, int links) const {
  const int first = addRodChain(system, start, end, links, mass, particles::parseRodForm(rod));
  addGravity(system, gravity);
  return first;
}

}  // namespace scenes

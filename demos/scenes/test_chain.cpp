#include "scenes/test_chain.h"

#include <algorithm>
#include <memory>

#include "particles/check.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"
#include "scenes/world.h"

namespace scenes {

void TestChainParams::validate() const {
  requireAtLeast("cl", cl, 2);
  requireWithinLimit("cl particles", cl, SceneLimits::particles);
  particles::requirePositive("length", length);
  particles::requirePositive("mass", mass);
  particles::parseRodForm(rod);
  particles::requireFinite("gravity", gravity);
  particles::requirePositive("tip-mass-ratio", tipMassRatio);
}

TestChainParams TestChainParams::seed() {
  TestChainParams p;
  p.cl = 12;
  p.length = 0.1;
  p.mass = 1.0;
  p.rod = "squared";
  p.gravity = kSeedGravity;
  p.tipMassRatio = 1.0;
  p.dt = 0.01;
  return p;
}

Scene buildTestChain(const TestChainParams& p) {
  Scene scene;
  scene.name = "test-chain";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;

  const int links = p.cl - 1;
  const double span = links * p.length;
  const int pin = addRodChain(s, Eigen::Vector2d::Zero(), Eigen::Vector2d(span, 0.0), links, p.mass,
                              particles::parseRodForm(p.rod));
  s.setPinned(pin, true);
  s.setMass(pin + links, p.tipMassRatio * p.mass);
  addGravity(s, p.gravity);

  // The pin at the centre; the chain swings through the lower half, so the
  // view is that half and a little above the pin.
  scene.viewMin = Eigen::Vector2d(-1.05 * span, -1.05 * span);
  scene.viewMax = Eigen::Vector2d(1.05 * span, 0.15 * span);
  return scene;
}

}  // namespace scenes

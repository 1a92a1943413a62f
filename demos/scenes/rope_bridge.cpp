#include "scenes/rope_bridge.h"

#include <cmath>
#include <memory>

#include "particles/check.h"
#include "particles/forces/spring.h"
#include "scene_limits.h"
#include "scenes/param_fields.h"

namespace scenes {

void RopeBridgeParams::validate() const {
  requireAtLeast("planks", planks, 2);
  requireWithinLimit("planks", planks, 10000);
  particles::requirePositive("span", span);
  particles::requireInRange("slack", slack, 0.0, 1.0);
  particles::requirePositive("plank-mass", plankMass);
  particles::requirePositive("stiffness", stiffness);
  particles::requireNonNegative("damping", damping);
  requireAtLeast("balls", balls, 0);
  requireWithinLimit("balls", balls, 100);
  particles::requirePositive("ball-radius", ballRadius);
  particles::requirePositive("ball-mass", ballMass);
  particles::requireInRange("restitution", restitution, 0.0, 1.0);
  particles::requireNonNegative("gravity", gravity);
}

RopeBridgeParams RopeBridgeParams::seed() {
  RopeBridgeParams p;
  p.gravity = kSeedGravity;
  p.dt = 0.005;
  return p;
}

Scene buildRopeBridge(const RopeBridgeParams& p) {
  Scene scene;
  scene.name = "rope-bridge";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;
  const int links = p.planks + 1;
  const double rest = p.span * (1.0 + p.slack) / links;  // the rope's length shared by its links
  // Hung as a parabola of the rope's length: sag d with arc ≈ span (1 + 8 d²/(3 span²)).
  const double sag = p.span * std::sqrt(3.0 * p.slack / 8.0);
  std::vector<Eigen::Vector2d> positions;
  for (int k = 0; k <= links; ++k) {
    const double u = static_cast<double>(k) / links, x = p.span * (u - 0.5);
    positions.push_back({x, -4.0 * sag * u * (1.0 - u)});
  }
  std::vector<double> masses(positions.size(), p.plankMass);
  const int first = s.addParticles(positions, masses);
  s.setPinned(first, true);
  s.setPinned(first + links, true);
  const double plank = 0.5 * p.span / links;  // discs that touch along the span
  for (int k = 0; k <= links; ++k) s.setCollidable(first + k, plank);
  for (int k = 0; k < links; ++k)
    s.addForce(std::make_unique<particles::SpringForce>(first + k, first + k + 1, rest, p.stiffness, p.damping));
  // The balls, spread along the bridge, each a little higher above it than
  // the last: they land one after another and roll down into the dip.
  for (int b = 0; b < p.balls; ++b) {
    const double u = 0.1 + 0.8 * (b + 0.5) / p.balls, x = p.span * (u - 0.5);
    const Eigen::Vector2d at(x, -4.0 * sag * u * (1.0 - u) + plank + p.ballRadius + 0.08 * p.span * (1 + b));
    const int ball = s.addParticle(at, p.ballMass);
    s.setCollidable(ball, p.ballRadius);
  }
  s.contactSettings().particleRestitution = p.restitution;
  addGravity(s, p.gravity);
  scene.viewMin = Eigen::Vector2d(-0.6 * p.span - 0.05, -sag - 0.35 * p.span);
  scene.viewMax = Eigen::Vector2d(0.6 * p.span + 0.05, 0.08 * p.span * (p.balls + 1) + 2.0 * p.ballRadius + 0.05);
  return scene;
}

}  // namespace scenes

#include "scenes/oscillator.h"

#include <cmath>
#include <memory>

#include "particles/check.h"
#include "particles/forces/spring.h"
#include "scenes/param_fields.h"

namespace scenes {

void OscillatorParams::validate() const {
  particles::requirePositive("mass", mass);
  particles::requirePositive("stiffness", stiffness);
  particles::requireNonNegative("damping", damping);
  particles::requirePositive("rest", rest);
  // The mass must not reach the anchor, where the spring's direction is undefined.
  particles::requireInRange("stretch", stretch, -0.99 * rest, 10.0 * rest);
}

OscillatorParams OscillatorParams::seed() {
  OscillatorParams p;
  p.mass = 1.0;
  p.stiffness = 1.0;
  p.damping = 0.1;
  p.rest = 0.5;
  p.stretch = 0.3;
  p.dt = 0.01;
  return p;
}

Scene buildOscillator(const OscillatorParams& p) {
  Scene scene;
  scene.name = "oscillator";
  scene.dt = p.dt;
  scene.system = std::make_unique<particles::ParticleSystem>();
  particles::ParticleSystem& s = *scene.system;
  const int anchor = s.addParticle(Eigen::Vector2d::Zero(), p.mass);
  s.setPinned(anchor, true);
  const int bob = s.addParticle(Eigen::Vector2d(p.rest + p.stretch, 0.0), p.mass);
  s.addForce(std::make_unique<particles::SpringForce>(bob, anchor, p.rest, p.stiffness, p.damping));
  return scene;
}

double oscillatorDisplacement(const OscillatorParams& p, double t) {
  const double gamma = p.damping / (2.0 * p.mass);
  const double w0squared = p.stiffness / p.mass;
  const double disc = w0squared - gamma * gamma;
  const double decay = std::exp(-gamma * t);
  if (disc > 0.0) {
    const double wd = std::sqrt(disc);
    return p.stretch * decay * (std::cos(wd * t) + (gamma / wd) * std::sin(wd * t));
  }
  if (disc == 0.0) return p.stretch * decay * (1.0 + gamma * t);
  const double root = std::sqrt(-disc), r1 = -gamma + root, r2 = -gamma - root;
  return p.stretch * (r1 * std::exp(r2 * t) - r2 * std::exp(r1 * t)) / (r1 - r2);
}

}  // namespace scenes

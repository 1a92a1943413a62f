#pragma once
// What the two scenes of a rod chain riding on circular wires share
// (rod_chain.h: one wire under the first bead; taut_chain.h: one under each
// end): the particles' mass, the rod form, gravity and the step. Each scene's
// Params adds its number of links, its geometry and their defaults.
#include <string>

#include "particles/particle_system.h"
#include "scenes/world.h"

namespace scenes {

struct ChainOnWiresParams {
  double mass = 0.1;               // of each particle, kg
  std::string rod = "squared";     // rod constraint form
  double gravity = kEarthGravity;  // m/s²
  double dt = 0.002;               // the step the scene runs with, s

  // The shared fields, after the scene's own in its visit().
  template <class Visit>
  void visitShared(Visit&& field) {
    field("mass", mass, "mass of each particle, kg");
    field("rod", rod, "rod constraint form: squared (|d|^2 - r^2) or root (|d| - r)");
    field("gravity", gravity, "downward acceleration, m/s^2");
  }
  void validateShared(int links) const;  // links ≥ 1 within the particle limit, and the shared fields
  void useSeedValues();                  // preset "seed": the seed report's mass, gravity and dt

  // The chain of `links` rods from start to end, and gravity; returns the
  // first particle's index (addRodChain).
  int addChain(particles::ParticleSystem& system, const Eigen::Vector2d& start, const Eigen::Vector2d& end,
               int links) const;
};

}  // namespace scenes

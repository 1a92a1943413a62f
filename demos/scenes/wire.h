#pragma once
#include "scene.h"
#include "scenes/world.h"

namespace scenes {

// Beads on circular wires side by side under gravity, each released at rest
// at its own angle, neighbouring beads joined by a soft spring so the
// pendulums trade energy.
// Defaults: each pendulum alone swings with 2π√(r/g) = 1.0 s; the coupling
// k_s/m = g/r makes the springs as strong as gravity's restoring force.
struct WireParams {
  int beads = 3;
  double radius = 0.25;            // m
  double mass = 1.0;               // kg
  double coupling = 40.0;          // N/m
  double gravity = kEarthGravity;  // m/s²
  double dt = 0.005;               // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("beads", beads, "number of beads, one wire each");
    field("radius", radius, "wire radius, m");
    field("mass", mass, "mass of each bead, kg");
    field("coupling", coupling, "k_s of the spring between neighbouring beads, N/m (0: none)");
    field("gravity", gravity, "downward acceleration, m/s^2");
  }
  void validate() const;
  static WireParams seed();  // preset "seed": the seed report's values
};

Scene buildWire(const WireParams& p);

}  // namespace scenes

#pragma once
#include "scene.h"

namespace scenes {

// Beads on circular wires side by side under gravity, each released at rest
// at its own angle, neighbouring beads joined by a soft spring so the
// pendulums trade energy.
struct WireParams {
  int beads = 3;
  double radius = 0.25;
  double mass = 1.0;
  double coupling = 0.2;
  double gravity = 0.05;

  double dt = 0.01;  // the step the scene runs with, s

  template <class Visit>
  void visit(Visit&& field) {
    field("beads", beads, "number of beads, one wire each");
    field("radius", radius, "wire radius, world units");
    field("mass", mass, "mass of each bead");
    field("coupling", coupling, "k_s of the spring between neighbouring beads, force/length (0: none)");
    field("gravity", gravity, "downward acceleration, world units/s^2");
  }
  void validate() const;
  static WireParams seed();  // preset "seed": the seed report's values
};

Scene buildWire(const WireParams& p);

}  // namespace scenes
